//! Colours of parts and of moving subsets, shared by every picture so that a part has
//! the same colour in the sphere, the renders, the glTF file and the HTML viewer.
//!
//! A part whose name is a colour word ("red", "turquoise", "light-blue" …) gets that
//! colour; the others get distinct colours from a palette, skipping those already taken.

/// An sRGB colour, 8 bits per channel.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Rgb(pub u8, pub u8, pub u8);

impl Rgb {
    /// `#rrggbb`.
    pub fn hex(self) -> String {
        format!("#{:02x}{:02x}{:02x}", self.0, self.1, self.2)
    }

    /// Channels as fractions of 255 (sRGB, not linear).
    pub fn unit(self) -> [f64; 3] {
        [self.0, self.1, self.2].map(|c| c as f64 / 255.0)
    }

    /// Channels in linear light (what glTF's `baseColorFactor` expects).
    pub fn linear(self) -> [f64; 3] {
        self.unit().map(|c| {
            if c <= 0.04045 {
                c / 12.92
            } else {
                ((c + 0.055) / 1.055).powf(2.4)
            }
        })
    }
}

/// The grey of parts that are not highlighted.
pub const GREY: Rgb = Rgb(200, 200, 204);

/// Background of the renders.
pub const BACKGROUND: Rgb = Rgb(255, 255, 255);

/// Colour words a part may be named after, tuned to read well when shaded on white.
const NAMED: [(&str, Rgb); 24] = [
    ("red", Rgb(214, 39, 40)),
    ("green", Rgb(44, 160, 44)),
    ("blue", Rgb(31, 119, 220)),
    ("purple", Rgb(148, 103, 189)),
    ("violet", Rgb(148, 103, 189)),
    ("yellow", Rgb(240, 200, 20)),
    ("turquoise", Rgb(32, 200, 190)),
    ("cyan", Rgb(23, 190, 207)),
    ("orange", Rgb(255, 127, 14)),
    ("magenta", Rgb(220, 60, 190)),
    ("pink", Rgb(240, 130, 190)),
    ("brown", Rgb(140, 86, 75)),
    ("olive", Rgb(170, 170, 30)),
    ("teal", Rgb(0, 128, 128)),
    ("navy", Rgb(40, 60, 150)),
    ("maroon", Rgb(128, 20, 30)),
    ("lime", Rgb(130, 210, 40)),
    ("gold", Rgb(212, 160, 23)),
    ("silver", Rgb(170, 170, 175)),
    ("grey", Rgb(128, 128, 128)),
    ("gray", Rgb(128, 128, 128)),
    ("black", Rgb(60, 60, 60)),
    ("white", Rgb(235, 235, 235)),
    ("beige", Rgb(225, 205, 160)),
];

/// Distinct colours for parts without a colour name (no greys: grey means "not
/// highlighted"): strong colours first, then lighter and darker variants.
const PALETTE: [Rgb; 24] = [
    Rgb(31, 119, 180),
    Rgb(255, 127, 14),
    Rgb(44, 160, 44),
    Rgb(214, 39, 40),
    Rgb(148, 103, 189),
    Rgb(140, 86, 75),
    Rgb(227, 119, 194),
    Rgb(188, 189, 34),
    Rgb(23, 190, 207),
    Rgb(174, 199, 232),
    Rgb(255, 187, 120),
    Rgb(152, 223, 138),
    Rgb(255, 152, 150),
    Rgb(197, 176, 213),
    Rgb(196, 156, 148),
    Rgb(219, 219, 141),
    Rgb(57, 59, 121),
    Rgb(99, 121, 57),
    Rgb(140, 109, 49),
    Rgb(132, 60, 57),
    Rgb(123, 65, 115),
    Rgb(0, 128, 128),
    Rgb(158, 218, 229),
    Rgb(247, 182, 210),
];

/// The colour a part's name asks for, if it is a colour word (case and the prefixes
/// "light"/"dark" are understood: "Dark-Green", "light_blue").
pub fn named_color(name: &str) -> Option<Rgb> {
    let lower = name.to_ascii_lowercase();
    let word: String = lower.chars().filter(|c| c.is_ascii_alphabetic()).collect();
    let (shade, base) = if let Some(rest) = word.strip_prefix("light") {
        (1, rest)
    } else if let Some(rest) = word.strip_prefix("dark") {
        (-1, rest)
    } else {
        (0, word.as_str())
    };
    let c = NAMED.iter().find(|(n, _)| *n == base)?.1;
    Some(match shade {
        1 => mix(c, Rgb(255, 255, 255), 0.45),
        -1 => mix(c, Rgb(0, 0, 0), 0.4),
        _ => c,
    })
}

/// `a` moved a fraction `t` of the way to `b`.
pub fn mix(a: Rgb, b: Rgb, t: f64) -> Rgb {
    let f = |x: u8, y: u8| (x as f64 + (y as f64 - x as f64) * t).round() as u8;
    Rgb(f(a.0, b.0), f(a.1, b.1), f(a.2, b.2))
}

/// One colour per part, in part order: the colour the name asks for, else the next
/// palette colour not taken by a named part.
pub fn part_colors<S: AsRef<str>>(names: &[S]) -> Vec<Rgb> {
    let named: Vec<Option<Rgb>> = names.iter().map(|n| named_color(n.as_ref())).collect();
    let taken: Vec<Rgb> = named.iter().flatten().copied().collect();
    let mut free = PALETTE
        .iter()
        .copied()
        .filter(|c| !taken.contains(c))
        .cycle();
    named
        .into_iter()
        .map(|c| c.unwrap_or_else(|| free.next().unwrap_or(PALETTE[0])))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colour_words_are_understood() {
        assert_eq!(named_color("Red"), Some(Rgb(214, 39, 40)));
        assert_eq!(named_color("turquoise"), Some(Rgb(32, 200, 190)));
        assert!(named_color("light-blue").is_some());
        assert_eq!(named_color("bolt"), None);
    }

    #[test]
    fn unnamed_parts_get_distinct_colours_not_taken_by_named_ones() {
        let names = ["red", "a", "b", "c"];
        let c = part_colors(&names);
        assert_eq!(c[0], Rgb(214, 39, 40));
        for i in 0..4 {
            for j in 0..i {
                assert_ne!(c[i], c[j]);
            }
        }
    }

    #[test]
    fn linear_light_is_darker_than_srgb() {
        let l = Rgb(128, 128, 128).linear();
        assert!((l[0] - 0.2158).abs() < 1e-3);
    }
}
