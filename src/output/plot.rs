//! Drawing helpers shared by the figures (plotters, with the DejaVu Sans shipped in
//! `assets/fonts/`, so that no system font is needed: PNG text is drawn by
//! [`super::raster::Raster`], SVG text names [`FONT`]).

use super::FileError;
use super::raster::Raster;
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::element::ComposedElement;
use plotters::prelude::*;
use plotters::style::{FontStyle, register_font};
use std::path::Path;
use std::sync::Once;

static REGISTERED: Once = Once::new();

/// The font family of every figure's text. An SVG names it as is (DejaVu Sans where
/// the viewer has it, else its sans-serif); plotters measures text with the shipped
/// DejaVu Sans registered under this name, and the PNGs draw with it.
pub const FONT: &str = "DejaVu Sans, sans-serif";

/// Registers the shipped font under [`FONT`] once.
pub fn init_font() {
    REGISTERED.call_once(|| {
        let _ = register_font(FONT, FontStyle::Normal, super::raster::DEJAVU_SANS);
    });
}

/// The Okabe–Ito palette (Okabe and Ito, *Color Universal Design*, 2008): eight colours
/// that readers with any common colour-vision deficiency tell apart. Every figure
/// takes its categorical colours from here, so that a colour means the same kind of
/// thing across the book.
pub mod okabe_ito {
    use plotters::style::RGBColor;

    /// Black.
    pub const BLACK: RGBColor = RGBColor(0, 0, 0);
    /// Orange.
    pub const ORANGE: RGBColor = RGBColor(230, 159, 0);
    /// Sky blue.
    pub const SKY_BLUE: RGBColor = RGBColor(86, 180, 233);
    /// Bluish green.
    pub const BLUISH_GREEN: RGBColor = RGBColor(0, 158, 115);
    /// Yellow (too light for a line on white: for areas and cells).
    pub const YELLOW: RGBColor = RGBColor(240, 228, 66);
    /// Blue.
    pub const BLUE: RGBColor = RGBColor(0, 114, 178);
    /// Vermillion.
    pub const VERMILLION: RGBColor = RGBColor(213, 94, 0);
    /// Reddish purple.
    pub const REDDISH_PURPLE: RGBColor = RGBColor(204, 121, 167);

    /// The order in which a figure's data series take their colours: the three
    /// strongest first (blue, vermillion, bluish green), orange last (beside
    /// vermillion it is the pair most often confused), yellow left out (it does not
    /// show as a line on white) and black kept for references.
    pub const SERIES: [RGBColor; 6] = [
        BLUE,
        VERMILLION,
        BLUISH_GREEN,
        REDDISH_PURPLE,
        SKY_BLUE,
        ORANGE,
    ];

    /// The colour of the `i`-th data series ([`SERIES`], cycled).
    pub fn series(i: usize) -> RGBColor {
        SERIES[i % SERIES.len()]
    }
}

/// Neutral greys for what is not data: reference lines and guides ([`GREY_DARK`]), a
/// second reference ([`GREY`]), backgrounds and "nothing here" ([`GREY_LIGHT`]).
pub const GREY_DARK: RGBColor = RGBColor(60, 60, 60);
/// See [`GREY_DARK`].
pub const GREY: RGBColor = RGBColor(120, 120, 120);
/// See [`GREY_DARK`].
pub const GREY_LIGHT: RGBColor = RGBColor(210, 210, 210);

/// The sequential colour map of every figure that colours a value: viridis (van der
/// Walt and Smith, matplotlib 2.0), dark purple at `s = 0` through blue and green to
/// yellow at `s = 1`, uniform in perceived lightness and readable in grey and by
/// colour-blind readers. Linear between its nine stops at every eighth; `s` outside
/// [0, 1] is clamped, and NaN is drawn as `s = 0`.
pub fn viridis(s: f64) -> RGBColor {
    const STOPS: [[f64; 3]; 9] = [
        [68.0, 1.0, 84.0],
        [72.0, 40.0, 120.0],
        [62.0, 73.0, 137.0],
        [49.0, 104.0, 142.0],
        [38.0, 130.0, 142.0],
        [31.0, 158.0, 137.0],
        [53.0, 183.0, 121.0],
        [110.0, 206.0, 88.0],
        [253.0, 231.0, 37.0],
    ];
    let s = if s.is_nan() { 0.0 } else { s.clamp(0.0, 1.0) };
    let at = s * 8.0;
    let i = (at.floor() as usize).min(7);
    let w = at - i as f64;
    let mix = |j: usize| (STOPS[i][j] + w * (STOPS[i + 1][j] - STOPS[i][j])).round() as u8;
    RGBColor(mix(0), mix(1), mix(2))
}

/// Colour of a contact regime (`branch4` and beyond cycle through further colours, so
/// a law with more branches draws too).
pub fn regime_colour(regime: &str) -> RGBColor {
    use okabe_ito as oi;
    const MORE: [RGBColor; 4] = [oi::SKY_BLUE, oi::REDDISH_PURPLE, oi::YELLOW, GREY_DARK];
    use crate::law::Regime;
    match regime.parse::<Regime>() {
        Ok(Regime::NoContact) => GREY,
        Ok(Regime::Branch(1)) => oi::BLUE,
        Ok(Regime::Branch(2)) => oi::ORANGE,
        Ok(Regime::Branch(3)) => oi::BLUISH_GREEN,
        Ok(Regime::Limit) => oi::VERMILLION,
        Ok(Regime::Branch(b)) => MORE[b.saturating_sub(4) % MORE.len()],
        Err(_) => oi::BLACK,
    }
}

/// Human label of a regime.
pub fn regime_label(regime: &str) -> &'static str {
    match regime {
        "no_contact" => "no contact (uν ≤ 0)",
        "branch1" => "branch 1 (0 < uν ≤ u¹)",
        "branch2" => "branch 2 (u¹ < uν < u², softening)",
        "branch3" => "branch 3 (uν ≥ u²)",
        "limit" => "at the limit uν = g",
        _ => "other",
    }
}

/// The contact regimes the figures count and colour, in this order (see [`regime_label`]).
pub const REGIMES: [&str; 5] = ["no_contact", "branch1", "branch2", "branch3", "limit"];

/// The candidate key points of a log axis that lie inside its range `(lo, hi)`:
/// plotters draws a key point outside the range at the edge of the label area, as a
/// stray axis line.
pub fn keys_within(range: (f64, f64), candidates: impl IntoIterator<Item = f64>) -> Vec<f64> {
    candidates
        .into_iter()
        .filter(|x| *x >= range.0 && *x <= range.1)
        .collect()
}

/// A figure that can be drawn on any plotters backend.
pub trait Figure {
    /// Draws the figure on `root`; an error is said in words.
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), String>;
}

/// The legend box of every figure: `font`-point labels on white of the given opacity,
/// with a black border, at `position`.
pub fn legend<'a, DB, CT>(
    chart: &mut ChartContext<'a, DB, CT>,
    position: SeriesLabelPosition,
    font: u32,
    opacity: f64,
) -> Result<(), String>
where
    DB: DrawingBackend + 'a,
    CT: plotters::coord::CoordTranslate,
{
    chart
        .configure_series_labels()
        .position(position)
        .label_font((FONT, font))
        .background_style(WHITE.mix(opacity))
        .border_style(BLACK)
        .draw()
        .map_err(e2s)
}

/// Writes `title` across the top of `root` and returns the area below it. The title
/// keeps `size` where it fits the width; a longer one is split at the "; " nearest its
/// middle into two lines, and shrunk (to no less than 12 points) until every line
/// fits, so that no figure clips its title.
pub fn fit_title<DB: DrawingBackend>(
    root: &DrawingArea<DB, plotters::coord::Shift>,
    title: &str,
    size: u32,
) -> Result<DrawingArea<DB, plotters::coord::Shift>, String> {
    let room = root.dim_in_pixel().0.saturating_sub(24);
    let fits = |lines: &[&str], s: u32| -> Result<bool, String> {
        for l in lines {
            if root
                .estimate_text_size(l, &(FONT, s).into_text_style(root))
                .map_err(e2s)?
                .0
                > room
            {
                return Ok(false);
            }
        }
        Ok(true)
    };
    let lines: Vec<&str> = if fits(&[title], size)? {
        vec![title]
    } else {
        let middle = title.len() / 2;
        match title
            .match_indices("; ")
            .min_by_key(|(i, _)| i.abs_diff(middle))
        {
            Some((i, _)) => vec![&title[..i], &title[i + 2..]],
            None => vec![title],
        }
    };
    let mut s = size;
    while s > 12 && !fits(&lines, s)? {
        s -= 1;
    }
    let mut area = root.clone();
    for l in lines {
        area = area.titled(l, (FONT, s)).map_err(e2s)?;
    }
    Ok(area)
}

/// A legend beside a chart rather than on its data: `entries` (label, colour, dashed)
/// drawn top down in `area`, a short line sample before each label.
pub fn side_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    entries: &[(String, RGBColor, bool)],
    font: u32,
) -> Result<(), String> {
    let step = (font as i32 * 3) / 2;
    let top = 40;
    for (k, (label, colour, dashed)) in entries.iter().enumerate() {
        let y = top + k as i32 * step;
        let style = colour.stroke_width(3);
        if *dashed {
            for x in [4, 14, 24] {
                area.draw(&PathElement::new(vec![(x, y), (x + 6, y)], style))
                    .map_err(e2s)?;
            }
        } else {
            area.draw(&PathElement::new(vec![(4, y), (30, y)], style))
                .map_err(e2s)?;
        }
        area.draw(&Text::new(
            label.clone(),
            (36, y - font as i32 / 2),
            (FONT, font).into_font(),
        ))
        .map_err(e2s)?;
    }
    Ok(())
}

/// Maps any displayable error to a string.
pub fn e2s<E: std::fmt::Display>(e: E) -> String {
    e.to_string()
}

/// Draws `fig` into both `stem.png` and `stem.svg` (each written to a temporary
/// file, then renamed), the two at once on two threads.
pub fn both<F: Figure + Sync>(
    dir: &Path,
    stem: &str,
    size: (u32, u32),
    fig: &F,
) -> Result<(), FileError> {
    init_font();
    std::fs::create_dir_all(dir).map_err(|e| FileError::Io {
        path: dir.display().to_string(),
        source: e,
    })?;
    let one = |ext: &str| -> Result<(), FileError> {
        let final_path = dir.join(format!("{stem}.{ext}"));
        let tmp = dir.join(format!(".{stem}.tmp-{}.{ext}", std::process::id()));
        let res = if ext == "png" {
            // Drawn in memory, then encoded and written here, so that a failed write
            // (a full disk) says its I/O error in words.
            let mut pixels = vec![0u8; 3 * size.0 as usize * size.1 as usize];
            let drawn = {
                let root = Raster::new(BitMapBackend::with_buffer(&mut pixels, size))
                    .map(|b| b.into_drawing_area());
                root.and_then(|root| {
                    root.fill(&WHITE)
                        .map_err(e2s)
                        .and_then(|_| fig.draw(&root))
                        .and_then(|_| root.present().map_err(e2s))
                })
            };
            drawn.and_then(|()| {
                image::save_buffer_with_format(
                    &tmp,
                    &pixels,
                    size.0,
                    size.1,
                    image::ColorType::Rgb8,
                    image::ImageFormat::Png,
                )
                .map_err(|e| format!("could not be written: {e}"))
            })
        } else {
            let mut text = String::new();
            let drawn = {
                let root = SVGBackend::with_string(&mut text, size).into_drawing_area();
                root.fill(&WHITE)
                    .map_err(e2s)
                    .and_then(|_| fig.draw(&root))
                    .and_then(|_| root.present().map_err(e2s))
            };
            drawn.and_then(|()| {
                std::fs::write(&tmp, text).map_err(|e| format!("could not be written: {e}"))
            })
        };
        if let Err(m) = res {
            let _ = std::fs::remove_file(&tmp);
            return Err(FileError::Plot {
                path: final_path.display().to_string(),
                message: m,
            });
        }
        std::fs::rename(&tmp, &final_path).map_err(|e| FileError::Io {
            path: final_path.display().to_string(),
            source: e,
        })
    };
    let (png, svg) = std::thread::scope(|s| {
        let png = s.spawn(|| one("png"));
        let svg = one("svg");
        (png.join().expect("the PNG thread"), svg)
    });
    png.and(svg)
}

/// A legend entry for a line with a filled circle marker: the line `2 * half` px long
/// in `style`, the circle of `radius` px at its middle.
pub fn circle_legend<DB: DrawingBackend>(
    (x, y): (i32, i32),
    half: i32,
    style: ShapeStyle,
    radius: i32,
    colour: RGBColor,
) -> CircleLegend<DB> {
    EmptyElement::at((x + half, y))
        + PathElement::new(vec![(-half, 0), (half, 0)], style)
        + Circle::new((0, 0), radius, colour.filled())
}

/// The element [`circle_legend`] draws.
pub type CircleLegend<DB> =
    ComposedElement<(i32, i32), DB, PathElement<(i32, i32)>, Circle<(i32, i32), i32>>;

/// A legend entry for a dashed guide: four dashes of `dash` px with `gap` px
/// between them, cut at 28 px, so the entry shows the guide's own pattern.
pub fn dashed_legend<DB: DrawingBackend>(
    (x, y): (i32, i32),
    dash: i32,
    gap: i32,
    style: ShapeStyle,
) -> DashedLegend<DB> {
    let seg = |i: i32| {
        let a = (i * (dash + gap)).min(28);
        PathElement::new(vec![(x + a, y), (x + (a + dash).min(28), y)], style)
    };
    EmptyElement::at((0, 0)) + seg(0) + seg(1) + seg(2) + seg(3)
}

/// The ends of the `i`-th slope guide of [`slope_guides`].
fn guide_ends(i: usize, slope: f64, (x0, y0): (f64, f64), xmax: f64, step: f64) -> [(f64, f64); 2] {
    let y0 = y0 * step.powi(i as i32 + 1);
    [(x0, y0), (xmax, y0 * (xmax / x0).powf(-slope))]
}

/// The lowest value [`slope_guides`] draws with the same arguments (so that a chart can
/// make room for the whole of each guide).
pub fn slope_guides_low(slopes: &[f64], start: (f64, f64), xmax: f64, step: f64) -> f64 {
    slopes
        .iter()
        .enumerate()
        .flat_map(|(i, &slope)| guide_ends(i, slope, start, xmax, step))
        .map(|p| p.1)
        .fold(f64::INFINITY, f64::min)
}

/// Dash patterns (dash, gap in pixels) of slope guides told apart at a glance: long
/// dashes, short dashes with wide gaps, dots.
pub const DISTINCT_DASHES: [(i32, i32); 3] = [(18, 5), (5, 8), (2, 4)];

/// The dash patterns the exact study's guides keep (long, medium, dots).
pub const EXACT_DASHES: [(i32, i32); 3] = [(14, 6), (6, 5), (2, 5)];

/// Dashed slope guides $y \propto x^{-\text{slope}}$ from `x0` to `xmax`, the $i$-th starting at
/// $y_0\,\text{step}^{i+1}$ (below the series it is compared with), the $i$-th in dash
/// pattern `dashes[i]` (cycled), shown in the legend as drawn.
pub fn slope_guides<'a, DB, CT>(
    chart: &mut ChartContext<'a, DB, CT>,
    guides: &[(f64, String)],
    dashes: &[(i32, i32)],
    start: (f64, f64),
    xmax: f64,
    step: f64,
) -> Result<(), String>
where
    DB: DrawingBackend + 'a,
    CT: plotters::coord::CoordTranslate<From = (f64, f64)>,
{
    for (i, (slope, label)) in guides.iter().enumerate() {
        let pts = guide_ends(i, *slope, start, xmax, step).to_vec();
        let grey = RGBColor(50, 50, 50);
        let (dash, gap) = dashes[i % dashes.len()];
        chart
            .draw_series(DashedLineSeries::new(
                pts,
                dash as u32,
                gap as u32,
                grey.stroke_width(2),
            ))
            .map_err(e2s)?
            .label(label.clone())
            .legend(move |xy| dashed_legend(xy, dash, gap, grey.stroke_width(2)));
    }
    Ok(())
}

/// The element [`dashed_legend`] draws: four path segments.
pub type DashedLegend<DB> = ComposedElement<
    (i32, i32),
    DB,
    Dash,
    ComposedElement<(i32, i32), DB, ComposedElement<(i32, i32), DB, Dash, Dash>, Dash>,
>;

type Dash = PathElement<(i32, i32)>;

/// A tick label's text from its value.
pub type Format<'f> = &'f dyn Fn(&f64) -> String;

/// The chart [`LogLogChart::build`] returns: on `DB`, axes `X` and `Y`.
pub type LogLogContext<'a, DB, X, Y> = ChartContext<
    'a,
    DB,
    Cartesian2d<<X as AsRangedCoord>::CoordDescType, <Y as AsRangedCoord>::CoordDescType>,
>;

/// The frame of a log–log chart, set up in one place for every figure that draws one:
/// the caption, the margin, the label areas, the axis descriptions, the tick labels'
/// text and the fonts. [`LogLogChart::default`] is the house style; a figure states only
/// where it differs. The axes (their ranges, log scales and key points) are the
/// figure's own, passed to [`LogLogChart::build`].
#[derive(Clone, Copy)]
pub struct LogLogChart<'t> {
    /// The caption and its font size.
    pub caption: (&'t str, u32),
    /// The margin around the chart, pixels.
    pub margin: u32,
    /// The height of the x labels' area and the width of the y labels', pixels.
    pub label_areas: (u32, u32),
    /// The axis descriptions, x then y.
    pub desc: (&'t str, &'t str),
    /// The tick labels' text, x then y (`None`: plotters' own).
    pub format: (Option<Format<'t>>, Option<Format<'t>>),
    /// The font size of the tick labels, and of the axis descriptions (`None`:
    /// plotters' own).
    pub fonts: (u32, Option<u32>),
}

impl Default for LogLogChart<'_> {
    fn default() -> Self {
        LogLogChart {
            caption: ("", 24),
            margin: 15,
            label_areas: (60, 80),
            desc: ("", ""),
            format: (None, None),
            fonts: (20, Some(20)),
        }
    }
}

impl<'t> LogLogChart<'t> {
    /// The chart on `area` with the axes `x` and `y` (log scales, with or without key
    /// points), its mesh, labels and descriptions drawn.
    pub fn build<'a, DB, X, Y>(
        &self,
        area: &'a DrawingArea<DB, plotters::coord::Shift>,
        x: X,
        y: Y,
    ) -> Result<LogLogContext<'a, DB, X, Y>, String>
    where
        DB: DrawingBackend + 'a,
        X: AsRangedCoord<Value = f64>,
        Y: AsRangedCoord<Value = f64>,
        X::CoordDescType: ValueFormatter<f64>,
        Y::CoordDescType: ValueFormatter<f64>,
    {
        let (x, y): (X::CoordDescType, Y::CoordDescType) = (x.into(), y.into());
        log_range(self.desc.0, x.range())?;
        log_range(self.desc.1, y.range())?;
        let mut chart = ChartBuilder::on(area)
            .caption(self.caption.0, (FONT, self.caption.1))
            .margin(self.margin)
            .x_label_area_size(self.label_areas.0)
            .y_label_area_size(self.label_areas.1)
            .build_cartesian_2d(x, y)
            .map_err(e2s)?;
        let mut mesh = chart.configure_mesh();
        mesh.x_desc(self.desc.0)
            .y_desc(self.desc.1)
            .label_style((FONT, self.fonts.0));
        if let Some(f) = self.format.0 {
            mesh.x_label_formatter(f);
        }
        if let Some(f) = self.format.1 {
            mesh.y_label_formatter(f);
        }
        if let Some(size) = self.fonts.1 {
            mesh.axis_desc_style((FONT, size));
        }
        mesh.draw().map_err(e2s)?;
        Ok(chart)
    }
}

/// The widest ratio of a log axis's ends that a chart draws readably (30 decades).
pub const MAX_LOG_SPAN: f64 = 1e30;

/// Refuses the range of a log axis (described as `axis`) that is not finite, positive
/// and increasing: plotters makes the key points of a log axis by stepping from its
/// lower end by a factor until it passes the upper, which from 0 never moves and to
/// $\infty$ never ends (a chart of a time of 0 spun; one of NaN allocated without
/// bound). An axis over more than [`MAX_LOG_SPAN`] is refused too: its labels would
/// run together, and from a subnormal end plotters' stepping takes hours.
pub fn log_range(axis: &str, range: std::ops::Range<f64>) -> Result<(), String> {
    let (lo, hi) = (range.start, range.end);
    if lo.is_finite() && hi.is_finite() && f64::MIN_POSITIVE <= lo && lo < hi {
        if hi / lo > MAX_LOG_SPAN {
            return Err(format!(
                "the log axis \"{axis}\" would span {lo:e} to {hi:e}, {:.0} decades; a chart \
                 shows at most {} (the data hold a value far from the others)",
                hi.log10() - lo.log10(),
                MAX_LOG_SPAN.log10()
            ));
        }
        Ok(())
    } else {
        Err(format!(
            "the log axis \"{axis}\" would span {lo:e} to {hi:e}; a log axis spans finite \
             numbers > 0, the lower below the upper (the data hold a value that is not a \
             finite number > 0, or none)"
        ))
    }
}

/// The smallest and largest $x$ and the smallest and largest $y$ of `points`, as
/// `((xmin, xmax), (ymin, ymax))`: the data range of a chart of positive values (the
/// maxima start from 0, the minima from $\infty$).
pub fn extent<'p>(points: impl IntoIterator<Item = &'p (f64, f64)>) -> ((f64, f64), (f64, f64)) {
    points.into_iter().fold(
        ((f64::INFINITY, 0.0), (f64::INFINITY, 0.0)),
        |((x0, x1), (y0, y1)), p| ((x0.min(p.0), x1.max(p.0)), (y0.min(p.1), y1.max(p.1))),
    )
}

/// The 1-2-5 points of the decades $10^e$, $e$ in `exponents`, that lie in `range`: the
/// key points of a log axis with a label at 1, 2 and 5 of each decade.
pub fn one_two_five(range: (f64, f64), exponents: std::ops::RangeInclusive<i32>) -> Vec<f64> {
    keys_within(
        range,
        exponents.flat_map(|e| [1.0, 2.0, 5.0].map(|m| m * 10f64.powi(e))),
    )
}

/// A tick label in plain decimals, to 6 significant digits, without an exponent:
/// "0.001", "0.5", "20", "1000".
pub fn plain(v: &f64) -> String {
    if *v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let digits = 5 - v.abs().log10().floor() as i32;
    let scale = 10f64.powi(digits);
    format!("{}", (v * scale).round() / scale)
}

/// A tick label of a log axis over many decades: a power of ten as "10⁻⁴" (Unicode
/// superscripts), any other value in [`plain`] decimals.
pub fn power_of_ten(v: &f64) -> String {
    let e = v.log10().round();
    if v.is_finite() && *v > 0.0 && (v / 10f64.powf(e) - 1.0).abs() < 1e-9 {
        let sup: String = format!("{}", e as i32)
            .chars()
            .map(|c| match c {
                '-' => '⁻',
                d => ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'][d as usize - '0' as usize],
            })
            .collect();
        format!("10{sup}")
    } else {
        plain(v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn viridis_runs_from_purple_to_yellow_getting_lighter() {
        assert_eq!(viridis(0.0), RGBColor(68, 1, 84));
        assert_eq!(viridis(1.0), RGBColor(253, 231, 37));
        assert_eq!(viridis(0.5), RGBColor(38, 130, 142));
        assert_eq!(viridis(-3.0), viridis(0.0));
        assert_eq!(viridis(7.0), viridis(1.0));
        assert_eq!(viridis(f64::NAN), viridis(0.0));
        // Luma rises strictly along the map, so that it reads in grey.
        let luma = |c: RGBColor| 0.299 * c.0 as f64 + 0.587 * c.1 as f64 + 0.114 * c.2 as f64;
        let l: Vec<f64> = (0..=64).map(|i| luma(viridis(i as f64 / 64.0))).collect();
        assert!(l.windows(2).all(|w| w[1] > w[0]), "{l:?}");
    }

    #[test]
    fn series_colours_are_distinct_and_cycle() {
        for i in 0..okabe_ito::SERIES.len() {
            for j in 0..i {
                assert_ne!(okabe_ito::series(i), okabe_ito::series(j));
            }
        }
        assert_eq!(okabe_ito::series(okabe_ito::SERIES.len()), okabe_ito::BLUE);
        assert!(!okabe_ito::SERIES.contains(&okabe_ito::YELLOW));
    }
}
