//! What the XML writers share ([`crate::stationxml`], [`crate::quakeml`]): text escaped for XML
//! 1.0 and the schema type `xs:dateTime` their dates must be.

/// `s` as XML character data or an attribute value: `&`, `<`, `>`, `"` and `'` escaped as
/// entities, and the control characters XML 1.0 does not allow (all below U+0020 but tab, line
/// feed and carriage return, and U+FFFE, U+FFFF) replaced by U+FFFD.
pub fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            '\t' | '\n' | '\r' => out.push(c),
            c if (c as u32) < 0x20 || c == '\u{FFFE}' || c == '\u{FFFF}' => out.push('\u{FFFD}'),
            c => out.push(c),
        }
    }
    out
}

/// Whether `s` is an `xs:dateTime` (XML Schema 1.0): `[-]YYYY-MM-DDThh:mm:ss[.s…][Z|±hh:mm]`, a
/// real date (no 30 February), hours 0–23 and seconds 0–59, a time zone within ±14:00.
pub fn is_xml_datetime(s: &str) -> bool {
    let b = s.as_bytes();
    let digits = |from: usize, n: usize| -> Option<i64> {
        let t = b.get(from..from + n)?;
        t.iter().all(u8::is_ascii_digit).then(|| t.iter().fold(0, |a, &d| 10 * a + i64::from(d - b'0')))
    };
    let mut i = usize::from(b.first() == Some(&b'-'));
    let year_len = b[i..].iter().take_while(|c| c.is_ascii_digit()).count();
    if year_len < 4 || (year_len > 4 && b[i] == b'0') {
        return false;
    }
    let Some(year) = digits(i, year_len.min(18)) else { return false };
    if year == 0 || year_len > 18 {
        return false;
    }
    i += year_len;
    let fixed = |i: usize, sep: u8| b.get(i) == Some(&sep);
    let (Some(month), Some(day), Some(hour), Some(minute), Some(second)) =
        (digits(i + 1, 2), digits(i + 4, 2), digits(i + 7, 2), digits(i + 10, 2), digits(i + 13, 2))
    else {
        return false;
    };
    if !(fixed(i, b'-') && fixed(i + 3, b'-') && fixed(i + 6, b'T') && fixed(i + 9, b':') && fixed(i + 12, b':')) {
        return false;
    }
    let leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
    let month_days = match month {
        1 | 3 | 5 | 7 | 8 | 10 | 12 => 31,
        4 | 6 | 9 | 11 => 30,
        2 if leap => 29,
        2 => 28,
        _ => return false,
    };
    if !(1..=month_days).contains(&day) || hour > 23 || minute > 59 || second > 59 {
        return false;
    }
    i += 15;
    if fixed(i, b'.') {
        let n = b[i + 1..].iter().take_while(|c| c.is_ascii_digit()).count();
        if n == 0 {
            return false;
        }
        i += 1 + n;
    }
    match b.get(i) {
        None => true,
        Some(b'Z') => i + 1 == b.len(),
        Some(b'+' | b'-') => match (digits(i + 1, 2), digits(i + 4, 2)) {
            (Some(h), Some(m)) => fixed(i + 3, b':') && i + 6 == b.len() && m <= 59 && h * 60 + m <= 14 * 60,
            _ => false,
        },
        Some(_) => false,
    }
}
