//! Text from files, made safe to print: messages never echo raw bytes or control
//! characters (a file name or a token holding `ESC [2J` must not clear the terminal).

/// `s` with every control character and every invisible formatting character (zero
/// widths, bidirectional overrides, byte-order marks) replaced by an escape: `\n`, `\t`,
/// `\r`, `\xNN` below U+0100, `\u{NNNN}` above. Printable text, backslashes included,
/// is kept as it is.
pub fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        push_escaped(&mut out, c);
    }
    out
}

fn push_escaped(out: &mut String, c: char) {
    use std::fmt::Write;
    match c {
        '\n' => out.push_str("\\n"),
        '\t' => out.push_str("\\t"),
        '\r' => out.push_str("\\r"),
        c if (c as u32) < 0x100 && c.is_control() => {
            let _ = write!(out, "\\x{:02x}", c as u32);
        }
        c if c.is_control() || invisible(c) => {
            let _ = write!(out, "\\u{{{:04x}}}", c as u32);
        }
        c => out.push(c),
    }
}

/// Formatting characters that change how the text around them is shown.
fn invisible(c: char) -> bool {
    matches!(c as u32,
        0x00ad | 0x061c | 0x180e | 0x200b..=0x200f | 0x2028..=0x202e | 0x2060..=0x206f
        | 0xfeff | 0xfff9..=0xfffb | 0xe0000..=0xe007f)
}

/// How many characters of a token [`quoted`] shows before cutting it.
const SHOWN: usize = 64;

/// A token from a file for a message: escaped, cut after 64 characters (marked by
/// `...`), between double quotes.
pub fn quoted(s: &str) -> String {
    let mut out = String::from("\"");
    for (i, c) in s.chars().enumerate() {
        if i == SHOWN {
            out.push_str("...");
            break;
        }
        push_escaped(&mut out, c);
    }
    out.push('"');
    out
}

/// A path for a message, escaped (file names may hold any byte but `/` and NUL).
pub fn path(p: &std::path::Path) -> String {
    escape(&p.to_string_lossy())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn control_characters_are_escaped() {
        assert_eq!(escape("a\x1b[2Jb\n\0"), "a\\x1b[2Jb\\n\\x00");
        assert_eq!(escape("é \\ x"), "é \\ x");
        assert_eq!(escape("\u{202e}evil\u{85}"), "\\u{202e}evil\\x85");
        assert_eq!(quoted("ab\u{7f}"), "\"ab\\x7f\"");
        let long = "x".repeat(100);
        assert_eq!(quoted(&long), format!("\"{}...\"", "x".repeat(64)));
        assert!(!escape(&String::from_utf8_lossy(b"\xff\x07")).contains('\x07'));
    }
}
