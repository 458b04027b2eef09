//! SVG to pixels with resvg: whole pictures (the sphere as PNG) and overlays (captions,
//! legends and arrows drawn over the z-buffer renders).
//!
//! Text needs fonts: the system's fonts are loaded once (Debian: `fonts-dejavu-core`);
//! without any, text is left out and the rest is drawn.

use resvg::tiny_skia::{Pixmap, Transform};
use resvg::usvg;
use std::sync::{Arc, OnceLock};

/// The font families the pictures ask for, best first.
pub const FONT_FAMILY: &str = "DejaVu Sans, Liberation Sans, Arial, Helvetica, sans-serif";

fn fonts() -> Arc<usvg::fontdb::Database> {
    static FONTS: OnceLock<Arc<usvg::fontdb::Database>> = OnceLock::new();
    FONTS
        .get_or_init(|| {
            let mut db = usvg::fontdb::Database::new();
            db.load_system_fonts();
            for family in ["DejaVu Sans", "Liberation Sans", "Arial"] {
                if db
                    .faces()
                    .any(|f| f.families.iter().any(|(n, _)| n == family))
                {
                    db.set_sans_serif_family(family);
                    break;
                }
            }
            Arc::new(db)
        })
        .clone()
}

/// True when at least one system font was found (text in the PNGs needs one).
pub fn fonts_available() -> bool {
    !fonts().is_empty()
}

fn parse(svg: &str) -> Option<usvg::Tree> {
    let opts = usvg::Options {
        fontdb: fonts(),
        font_family: "DejaVu Sans".into(),
        ..Default::default()
    };
    usvg::Tree::from_str(svg, &opts).ok()
}

/// Renders `svg` at `scale` × its own size on white; `None` when it does not parse.
pub fn svg_to_pixmap(svg: &str, scale: f32) -> Option<Pixmap> {
    let tree = parse(svg)?;
    let size = tree.size();
    let w = (size.width() * scale).ceil().max(1.0) as u32;
    let h = (size.height() * scale).ceil().max(1.0) as u32;
    let mut pixmap = Pixmap::new(w, h)?;
    pixmap.fill(resvg::tiny_skia::Color::WHITE);
    resvg::render(
        &tree,
        Transform::from_scale(scale, scale),
        &mut pixmap.as_mut(),
    );
    Some(pixmap)
}

/// Draws `svg` (same size as `pixmap`) over `pixmap`.
pub fn overlay(pixmap: &mut Pixmap, svg: &str) {
    if let Some(tree) = parse(svg) {
        resvg::render(&tree, Transform::identity(), &mut pixmap.as_mut());
    }
}

/// PNG bytes of an opaque pixmap.
pub fn png_bytes(pixmap: &Pixmap) -> Vec<u8> {
    pixmap
        .encode_png()
        .expect("encoding an in-memory pixmap cannot fail")
}

/// Escapes text for SVG.
pub fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}
