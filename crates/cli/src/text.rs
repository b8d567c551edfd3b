//! Text layout for a terminal, and printing that a closed pipe cannot stop.

/// `outln!` that ignores a failed write: a reader that went away (`stickslip pipeline … |
/// head -1`) must not stop a run before its tables and report are written (`outln!` panics on
/// a broken pipe).
macro_rules! outln {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stdout(), $($arg)*);
    }};
}

/// `errln!` that ignores a failed write (stderr piped into a reader that went away).
macro_rules! errln {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stderr(), $($arg)*);
    }};
}

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

pub use stickslip_ensemble::digest::{count, seed_list};

pub use stickslip_config::describe::N;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seed_lists_are_compact() {
        let hundred: Vec<u64> = (1..=100).rev().collect();
        assert_eq!(seed_list(&hundred), "1–100");
        assert_eq!(seed_list(&[200, 7, 123, 8, 1, 2, 3]), "1–3, 7, 8, 123, 200");
        assert_eq!(seed_list(&[]), "");
        assert_eq!(count(1, "seed", "seeds"), "1 seed");
        assert_eq!(count(2, "figure", "figures"), "2 figures");
    }

    #[test]
    fn combining_dots_take_no_column() {
        assert_eq!(width("Δt_m·λ·u̇_m/u̇_p"), 14);
        assert_eq!(pad("u̇", 3), "u̇  ");
    }
}
