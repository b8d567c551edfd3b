//! Text layout for a terminal.

/// Width of `s` as a terminal shows it: combining marks (e.g. the dot of u̇) take no column.
pub fn width(s: &str) -> usize {
    s.chars().filter(|c| !is_combining(*c)).count()
}

fn is_combining(c: char) -> bool {
    matches!(u32::from(c), 0x0300..=0x036F | 0x1AB0..=0x1AFF | 0x1DC0..=0x1DFF | 0x20D0..=0x20FF | 0xFE20..=0xFE2F)
}

/// `s` padded with spaces to `w` columns.
pub fn pad(s: &str, w: usize) -> String {
    format!("{s}{}", " ".repeat(w.saturating_sub(width(s))))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn combining_dots_take_no_column() {
        assert_eq!(width("Δt_m·λ·u̇_m/u̇_p"), 14);
        assert_eq!(pad("u̇", 3), "u̇  ");
    }
}
