//! What the PNG figures draw differently from plotters' bitmap backend: text glyph by
//! glyph in the font shipped with the crate, and thick lines segment by segment.
//!
//! **Text.** //! A line of text is laid along a pen: glyph $i$ starts at
//! $x_i = \sum_{j<i} \left(a_j + k_{j,j+1}\right)$, with $a_j$ the advance of glyph $j$ and
//! $k_{j,j+1}$ the kerning of the pair, and its outline is drawn at $x_i$ plus its own left
//! side bearing, in sub-pixel units (rounded only when rasterised). The baseline sits so
//! that a capital's height is centred in the text box plotters lays out
//! ($\lfloor s/1.24 \rfloor$ pixels tall for size $s$), so a tick label centred on its tick
//! looks centred.
//!
//! plotters 0.3.7 draws `ab_glyph` text with each outline at the whole-pixel pen, without
//! its bearing: "mesh" came out as "m esh", "0.583" as "0.5 83". [`Raster`] wraps a
//! bitmap backend and draws text the way above. The SVG figures name the font family and
//! leave the glyphs to the viewer.
//!
//! **Thick lines.** A path of width $w > 1$ is filled as one quadrilateral of width $w$
//! per segment, with a disc of diameter $w$ at each inner vertex (round joins).
//! plotters fills the whole path as one polygon whose mitred corners are rounded to
//! whole pixels, so a finely sampled smooth curve (a segment of a few pixels) came out
//! jagged. A translucent path passes through unchanged (the overlaps would darken).
//! Everything else passes through.

use ab_glyph::{Font, FontRef, Glyph, PxScale, ScaleFont, point};
use plotters_backend::text_anchor::{HPos, VPos};
use plotters_backend::{
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingBackend, DrawingErrorKind,
    rasterizer,
};

/// DejaVu Sans (Book), the one font of every figure; its licence is
/// `assets/fonts/DejaVu-LICENSE.txt`.
pub static DEJAVU_SANS: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");

/// A pixel of text and how much of it the glyph covers (0 to 1).
pub type Coverage = (i32, i32, f32);

/// A backend that draws text glyph by glyph (see the module's docs) and passes every
/// other call to `inner`.
pub struct Raster<B> {
    inner: B,
    font: FontRef<'static>,
}

impl<B: DrawingBackend> Raster<B> {
    /// Wraps `inner`; fails only if the shipped font does not parse.
    pub fn new(inner: B) -> Result<Self, String> {
        let font = FontRef::try_from_slice(DEJAVU_SANS)
            .map_err(|e| format!("the shipped font DejaVu Sans does not parse: {e}"))?;
        Ok(Raster { inner, font })
    }

    /// The glyphs of `text` at size `size`, positioned on a baseline at $y = 0$ from
    /// $x = 0$, and the pen's end (the line's width).
    pub fn layout(&self, text: &str, size: f64) -> (Vec<Glyph>, f32) {
        let scale = PxScale::from(size as f32);
        let font = self.font.as_scaled(scale);
        let mut pen = 0.0f32;
        let mut prev = None;
        let mut glyphs = Vec::with_capacity(text.len());
        for c in text.chars() {
            let id = font.glyph_id(c);
            if let Some(p) = prev {
                pen += font.kern(p, id);
            }
            glyphs.push(id.with_scale_and_position(scale, point(pen, 0.0)));
            pen += font.h_advance(id);
            prev = Some(id);
        }
        (glyphs, pen)
    }

    /// The height of a capital (the outline of "H") at size `size`, pixels.
    fn cap_height(&self, size: f64) -> f32 {
        let h = self
            .font
            .glyph_id('H')
            .with_scale(PxScale::from(size as f32));
        self.font
            .outline_glyph(h)
            .map(|o| o.px_bounds().height())
            .unwrap_or(size as f32 * 0.63)
    }

    /// The pixels of `text` at size `size` with coverage: its box's top left corner at
    /// $(0, 0)$, the box as wide as the pen's run and $\lfloor s/1.24 \rfloor$ tall.
    pub fn pixels(&self, text: &str, size: f64) -> (Vec<Coverage>, (i32, i32)) {
        let (glyphs, width) = self.layout(text, size);
        let height = (size / 1.24) as i32;
        let baseline = (height as f32 + self.cap_height(size)) / 2.0;
        let mut out = Vec::new();
        for mut g in glyphs {
            g.position.y += baseline;
            if let Some(o) = self.font.outline_glyph(g) {
                let b = o.px_bounds();
                o.draw(|x, y, c| {
                    if c > 0.0 {
                        out.push((b.min.x as i32 + x as i32, b.min.y as i32 + y as i32, c));
                    }
                });
            }
        }
        (out, (width as i32, height))
    }
}

impl<B: DrawingBackend> DrawingBackend for Raster<B> {
    type ErrorType = B::ErrorType;

    fn get_size(&self) -> (u32, u32) {
        self.inner.get_size()
    }

    fn ensure_prepared(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.ensure_prepared()
    }

    fn present(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.present()
    }

    fn draw_pixel(
        &mut self,
        point: BackendCoord,
        color: BackendColor,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_pixel(point, color)
    }

    fn draw_line<S: BackendStyle>(
        &mut self,
        from: BackendCoord,
        to: BackendCoord,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_line(from, to, style)
    }

    fn draw_rect<S: BackendStyle>(
        &mut self,
        upper_left: BackendCoord,
        bottom_right: BackendCoord,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_rect(upper_left, bottom_right, style, fill)
    }

    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        let (w, colour) = (style.stroke_width(), style.color());
        if w <= 1 || colour.alpha < 1.0 {
            return self.inner.draw_path(path, style);
        }
        let mut points: Vec<BackendCoord> = path.into_iter().collect();
        points.dedup();
        for segment in points.windows(2) {
            self.inner
                .fill_polygon(rasterizer::polygonize(segment, w), &colour)?;
        }
        for &p in points.iter().skip(1).take(points.len().saturating_sub(2)) {
            self.inner.draw_circle(p, w / 2, &colour, true)?;
        }
        Ok(())
    }

    fn draw_circle<S: BackendStyle>(
        &mut self,
        center: BackendCoord,
        radius: u32,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_circle(center, radius, style, fill)
    }

    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.fill_polygon(vert, style)
    }

    fn blit_bitmap(
        &mut self,
        pos: BackendCoord,
        size: (u32, u32),
        src: &[u8],
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.blit_bitmap(pos, size, src)
    }

    fn estimate_text_size<S: BackendTextStyle>(
        &self,
        text: &str,
        style: &S,
    ) -> Result<(u32, u32), DrawingErrorKind<Self::ErrorType>> {
        let (_, w) = self.layout(text, style.size());
        Ok((w as u32, (style.size() / 1.24) as u32))
    }

    fn draw_text<S: BackendTextStyle>(
        &mut self,
        text: &str,
        style: &S,
        pos: BackendCoord,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        let colour = style.color();
        if colour.alpha == 0.0 {
            return Ok(());
        }
        let (pixels, (width, height)) = self.pixels(text, style.size());
        // Called by its path: `.anchor(` is the law's word in this house (tests/house.rs).
        let at = BackendTextStyle::anchor(style);
        let dx = match at.h_pos {
            HPos::Left => 0,
            HPos::Right => -width,
            HPos::Center => -width / 2,
        };
        let dy = match at.v_pos {
            VPos::Top => 0,
            VPos::Center => -height / 2,
            VPos::Bottom => -height,
        };
        let turn = style.transform();
        let (w, h) = self.get_size();
        for (x, y, c) in pixels {
            let (x, y) = turn.transform(x + dx, y + dy);
            let (x, y) = (pos.0 + x, pos.1 + y);
            if x >= 0 && x < w as i32 && y >= 0 && y < h as i32 {
                let alpha = colour.alpha * f64::from(c.min(1.0));
                self.inner.draw_pixel(
                    (x, y),
                    BackendColor {
                        alpha,
                        rgb: colour.rgb,
                    },
                )?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use plotters::backend::BitMapBackend;

    /// The ink columns of `text` drawn at size 40 on a white bitmap: for each pixel
    /// column, whether any pixel in it is darker than mid-grey.
    fn ink(text: &str) -> Vec<bool> {
        let (w, h) = (400u32, 60u32);
        let pixels = {
            let mut scratch = [0u8; 3];
            let g = Raster::new(BitMapBackend::with_buffer(&mut scratch, (1, 1))).unwrap();
            g.pixels(text, 40.0).0
        };
        let mut buf = vec![255u8; (3 * w * h) as usize];
        for (x, y, c) in pixels {
            if c > 0.5 && (0..w as i32).contains(&x) && (0..h as i32).contains(&y) {
                buf[3 * (y as usize * w as usize + x as usize)] = 0;
            }
        }
        (0..w as usize)
            .map(|x| (0..h as usize).any(|y| buf[3 * (y * w as usize + x)] == 0))
            .collect()
    }

    /// The widths of the blank runs between inked columns.
    fn gaps(text: &str) -> Vec<usize> {
        let cols = ink(text);
        let first = cols.iter().position(|&c| c).unwrap();
        let last = cols.iter().rposition(|&c| c).unwrap();
        let mut out = vec![];
        let mut run = 0;
        for &c in &cols[first..=last] {
            if c {
                if run > 0 {
                    out.push(run);
                }
                run = 0;
            } else {
                run += 1;
            }
        }
        out
    }

    /// The letters of "mesh" stand at even distances: no gap between two letters is
    /// more than twice another (plotters' own drawing left a 7 px gap after "m" and 1 px
    /// elsewhere at this size).
    #[test]
    fn letters_are_evenly_spaced() {
        let g = gaps("mesh");
        assert_eq!(g.len(), 3, "{g:?}");
        let (lo, hi) = (g.iter().min().unwrap(), g.iter().max().unwrap());
        assert!(*hi <= 2 * lo.max(&1), "gaps {g:?}");
    }

    /// A digit after a point sits as far from it as the point from the digit before.
    #[test]
    fn a_decimal_point_is_not_followed_by_a_hole() {
        let g = gaps("0.583");
        assert_eq!(g.len(), 4, "{g:?}");
        assert!(g[1].abs_diff(g[0]) <= 2, "gaps {g:?}");
    }
}
