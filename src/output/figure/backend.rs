//! Where a figure is drawn: SVG or PNG by the file's extension, the
//! compiled-in font, and the error a drawing step reports.
//!
//! Text is set in DejaVu Sans, shipped in `assets/fonts` and compiled in, so
//! neither backend needs system font libraries.

use std::fmt;
use std::path::Path;
use std::sync::OnceLock;

use plotters::prelude::*;
use plotters::style::{register_font, FontStyle};

use super::Figure;

/// DejaVu Sans (Bitstream Vera licence, see `assets/fonts/LICENSE-DejaVu`).
static FONT: &[u8] = include_bytes!("../../../assets/fonts/DejaVuSans.ttf");
/// The font family the figures use (registered by [`register`]).
pub const FAMILY: &str = "sans-serif";

/// Register the built-in font as `sans-serif` for plotters (once; later
/// calls return the first result). Every figure of this crate draws and
/// measures its text with it, so call this before drawing.
pub fn register() -> Result<(), String> {
    static DONE: OnceLock<Result<(), String>> = OnceLock::new();
    DONE.get_or_init(|| {
        register_font(FAMILY, FontStyle::Normal, FONT)
            .map_err(|_| "the built-in font could not be loaded".to_string())
    })
    .clone()
}

/// The figure formats, by extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// `.svg`
    Svg,
    /// `.png`
    Png,
}

impl Format {
    /// The format of `path`, from its extension.
    pub fn of(path: &Path) -> Result<Self, String> {
        match path
            .extension()
            .and_then(|e| e.to_str())
            .map(|e| e.to_ascii_lowercase())
            .as_deref()
        {
            Some("svg") => Ok(Format::Svg),
            Some("png") => Ok(Format::Png),
            _ => Err(format!(
                "`{}`: unknown figure format; use a file name ending in .svg or .png",
                path.display()
            )),
        }
    }
}

/// A drawing step failed (the backend's message).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DrawError(pub String);

impl fmt::Display for DrawError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for DrawError {}

impl<E: std::error::Error + Send + Sync> From<DrawingAreaErrorKind<E>> for DrawError {
    fn from(e: DrawingAreaErrorKind<E>) -> Self {
        DrawError(e.to_string())
    }
}

/// Draw `figure` into `path`, SVG or PNG by its extension. The message of
/// an error names the file.
pub fn save(figure: &impl Figure, path: &Path) -> Result<(), String> {
    let format = Format::of(path)?;
    register()?;
    let size = figure.size();
    let fail = |e: String| format!("cannot draw `{}`: {e}", path.display());
    match format {
        Format::Svg => {
            let root = SVGBackend::new(path, size).into_drawing_area();
            figure.draw(&root).map_err(|e| fail(e.0))?;
            root.present().map_err(|e| fail(e.to_string()))
        }
        Format::Png => {
            let root = BitMapBackend::new(path, size).into_drawing_area();
            figure.draw(&root).map_err(|e| fail(e.0))?;
            root.present().map_err(|e| fail(e.to_string()))
        }
    }
}
