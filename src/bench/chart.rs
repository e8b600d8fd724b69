//! The benchmark charts, drawn with plotters: SVG as text (always), PNG as bytes (needs a font).
//!
//! A chart is a [`ChartSpec`]: points in groups (one colour and marker per group; one series per
//! method), optionally joined by lines, on logarithmic or linear axes. Logarithmic axes are drawn by
//! plotting `log10` of the values on linear axes and labelling the ticks with the values themselves.
//!
//! Text: the SVG backend writes `<text>` elements and needs no font, except that plotters measures
//! text for its layout through a font; [`svg`] wraps the backend so that it estimates text sizes from
//! the character count instead, so SVG never depends on the machine's fonts. The PNG backend
//! rasterises glyphs (plotters' `ab_glyph` feature): a TrueType font must be registered first with
//! [`register_font`] (the runner loads a system font such as DejaVu Sans); without one [`png`](fn@png) fails
//! with [`BenchError::Chart`] saying so. The legend is drawn here, not by plotters' series labels
//! (which always measure text through a font).

use super::BenchError;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters_backend::{
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingErrorKind,
};
use std::sync::atomic::{AtomicBool, Ordering};

/// One point of a chart.
#[derive(Clone, Debug, PartialEq)]
pub struct Point {
    /// A label drawn next to the marker (empty: none).
    pub label: String,
    /// The series (a method): one colour and marker per group, in the legend.
    pub group: String,
    /// The x value.
    pub x: f64,
    /// The y value.
    pub y: f64,
}

/// What to draw.
#[derive(Clone, Debug, PartialEq)]
pub struct ChartSpec {
    /// The caption.
    pub title: String,
    /// The x axis' description.
    pub x_desc: String,
    /// The y axis' description.
    pub y_desc: String,
    /// Logarithmic x axis.
    pub log_x: bool,
    /// Logarithmic y axis.
    pub log_y: bool,
    /// Join each group's points (sorted by x) with lines.
    pub lines: bool,
    /// The points; on a logarithmic axis, values that are not positive are left out.
    pub points: Vec<Point>,
    /// Lines of notes printed under the legend.
    pub notes: Vec<String>,
    /// Size in pixels.
    pub size: (u32, u32),
}

/// The value at which exact (zero) errors are drawn on the speed–accuracy chart.
pub const ZERO_ERROR_FLOOR: f64 = 1e-18;

/// The speed–accuracy chart: time per evaluation (log x) against the largest relative error (log y),
/// one marker per method (group) and robot (label). Errors of exactly 0 (exact rational evaluation)
/// are drawn at [`ZERO_ERROR_FLOOR`] and a note says so.
pub fn speed_accuracy(points: Vec<Point>) -> ChartSpec {
    let exact = points.iter().filter(|p| p.y == 0.0).count();
    let points: Vec<Point> = points
        .into_iter()
        .map(|p| Point {
            y: if p.y == 0.0 { ZERO_ERROR_FLOOR } else { p.y },
            ..p
        })
        .collect();
    let mut notes = Vec::new();
    if points.is_empty() {
        notes.push("no accuracy data in this run".to_string());
    }
    if exact > 0 {
        notes.push(format!(
            "{exact} point(s) with error exactly 0 drawn at {ZERO_ERROR_FLOOR:e}"
        ));
    }
    ChartSpec {
        title: "Speed against accuracy".into(),
        x_desc: "seconds per evaluation".into(),
        y_desc: "largest relative error".into(),
        log_x: true,
        log_y: true,
        lines: false,
        points,
        notes,
        size: (1000, 640),
    }
}

/// The scaling chart: derivation seconds (log y) against the number of joints of the generic chains,
/// one line per method.
pub fn scaling(points: Vec<Point>, notes: Vec<String>) -> ChartSpec {
    ChartSpec {
        title: "Derivation time of the generic n-joint chains".into(),
        x_desc: "joints n".into(),
        y_desc: "seconds".into(),
        log_x: false,
        log_y: true,
        lines: true,
        points,
        notes,
        size: (1000, 640),
    }
}

static FONT: AtomicBool = AtomicBool::new(false);

/// Registers the TrueType/OpenType font used for PNG text (`sans-serif`). Fails on bytes that are not
/// a font.
pub fn register_font(bytes: &'static [u8]) -> Result<(), BenchError> {
    plotters::style::register_font("sans-serif", FontStyle::Normal, bytes)
        .map_err(|_| BenchError::Chart("the font file is not a TrueType/OpenType font".into()))?;
    FONT.store(true, Ordering::SeqCst);
    Ok(())
}

/// Whether a font for PNG text has been registered.
pub fn has_font() -> bool {
    FONT.load(Ordering::SeqCst)
}

/// The chart as an SVG document.
pub fn svg(spec: &ChartSpec) -> Result<String, BenchError> {
    let mut out = String::new();
    {
        let root = NaiveText(SVGBackend::with_string(&mut out, spec.size)).into_drawing_area();
        draw(&root, spec)?;
        root.present().map_err(chart_err)?;
    }
    Ok(out)
}

/// The chart as PNG bytes; needs [`register_font`] first.
pub fn png(spec: &ChartSpec) -> Result<Vec<u8>, BenchError> {
    if !has_font() {
        return Err(BenchError::Chart(
            "PNG text needs a TrueType font and none was found (install fonts-dejavu-core, or set \
             SYMDYN_FONT to a .ttf file); the SVG charts are complete"
                .into(),
        ));
    }
    let (w, h) = spec.size;
    let mut buf = vec![255u8; (w * h * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buf, spec.size).into_drawing_area();
        draw(&root, spec)?;
        root.present().map_err(chart_err)?;
    }
    let mut bytes = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut bytes, w, h);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let mut writer = enc
            .write_header()
            .map_err(|e| BenchError::Chart(e.to_string()))?;
        writer
            .write_image_data(&buf)
            .map_err(|e| BenchError::Chart(e.to_string()))?;
    }
    Ok(bytes)
}

fn chart_err<E: std::fmt::Debug>(e: E) -> BenchError {
    BenchError::Chart(format!("{e:?}"))
}

const COLORS: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(23, 190, 207),
];

/// The groups in order of first appearance.
fn groups(points: &[Point]) -> Vec<&str> {
    let mut out: Vec<&str> = Vec::new();
    for p in points {
        if !out.contains(&p.group.as_str()) {
            out.push(&p.group);
        }
    }
    out
}

fn marker<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    k: usize,
    at: (i32, i32),
    color: RGBColor,
) -> Result<(), BenchError> {
    let style = color.filled();
    match k % 3 {
        0 => area.draw(&Circle::new(at, 5, style)),
        1 => area.draw(&TriangleMarker::new(at, 7, style)),
        _ => area.draw(&Cross::new(at, 5, Color::stroke_width(&color, 2))),
    }
    .map_err(chart_err)
}

fn tick_label(v: f64, log: bool) -> String {
    if log {
        let x = 10f64.powf(v);
        if (v - v.round()).abs() < 1e-9 {
            format!("1e{}", v.round() as i64)
        } else {
            format!("{x:.0e}")
        }
    } else if (v - v.round()).abs() < 1e-9 {
        format!("{}", v.round() as i64)
    } else {
        format!("{v:.1}")
    }
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    spec: &ChartSpec,
) -> Result<(), BenchError> {
    root.fill(&WHITE).map_err(chart_err)?;
    let (w, _) = spec.size;
    let (main, side) = root.split_horizontally(w.saturating_sub(260));
    let tx = |x: f64| if spec.log_x { x.log10() } else { x };
    let ty = |y: f64| if spec.log_y { y.log10() } else { y };
    let usable = |p: &&Point| {
        p.x.is_finite()
            && p.y.is_finite()
            && (!spec.log_x || p.x > 0.0)
            && (!spec.log_y || p.y > 0.0)
    };
    let pts: Vec<&Point> = spec.points.iter().filter(usable).collect();
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for p in &pts {
        x0 = x0.min(tx(p.x));
        x1 = x1.max(tx(p.x));
        y0 = y0.min(ty(p.y));
        y1 = y1.max(ty(p.y));
    }
    if pts.is_empty() {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    let pad = |a: f64, b: f64, log: bool| {
        let m = if log { 0.3 } else { ((b - a) * 0.05).max(0.5) };
        (a - m, b + m)
    };
    let (x0, x1) = pad(x0, x1, spec.log_x);
    let (y0, y1) = pad(y0, y1, spec.log_y);
    let mut chart = ChartBuilder::on(&main)
        .caption(&spec.title, ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(chart_err)?;
    let fx = |v: &f64| tick_label(*v, spec.log_x);
    let fy = |v: &f64| tick_label(*v, spec.log_y);
    chart
        .configure_mesh()
        .x_desc(spec.x_desc.as_str())
        .y_desc(spec.y_desc.as_str())
        .x_label_formatter(&fx)
        .y_label_formatter(&fy)
        .label_style(("sans-serif", 14))
        .draw()
        .map_err(chart_err)?;
    let gs = groups(&spec.points);
    for (k, g) in gs.iter().enumerate() {
        let color = COLORS[k % COLORS.len()];
        let mut series: Vec<(f64, f64)> = pts
            .iter()
            .filter(|p| p.group == *g)
            .map(|p| (tx(p.x), ty(p.y)))
            .collect();
        series.sort_by(|a, b| a.0.total_cmp(&b.0));
        if spec.lines && series.len() > 1 {
            chart
                .draw_series(LineSeries::new(
                    series.clone(),
                    Color::stroke_width(&color, 2),
                ))
                .map_err(chart_err)?;
        }
        let style = color.filled();
        let drawn = match k % 3 {
            0 => chart
                .draw_series(series.iter().map(|&p| Circle::new(p, 5, style)))
                .map(|_| ()),
            1 => chart
                .draw_series(series.iter().map(|&p| TriangleMarker::new(p, 7, style)))
                .map(|_| ()),
            _ => chart
                .draw_series(
                    series
                        .iter()
                        .map(|&p| Cross::new(p, 5, Color::stroke_width(&color, 2))),
                )
                .map(|_| ()),
        };
        drawn.map_err(chart_err)?;
    }
    let label_style = ("sans-serif", 12).into_font().color(&BLACK);
    chart
        .draw_series(pts.iter().filter(|p| !p.label.is_empty()).map(|p| {
            EmptyElement::at((tx(p.x), ty(p.y)))
                + Text::new(p.label.clone(), (7, -14), label_style.clone())
        }))
        .map_err(chart_err)?;
    // The legend and the notes, in the side panel.
    let text = ("sans-serif", 15).into_font().color(&BLACK);
    let small = ("sans-serif", 12).into_font().color(&BLACK);
    let mut y = 60;
    for (k, g) in gs.iter().enumerate() {
        let color = COLORS[k % COLORS.len()];
        if spec.lines {
            side.draw(&PathElement::new(
                vec![(4, y), (28, y)],
                Color::stroke_width(&color, 2),
            ))
            .map_err(chart_err)?;
        }
        marker(&side, k, (16, y), color)?;
        side.draw(&Text::new(g.to_string(), (38, y - 8), text.clone()))
            .map_err(chart_err)?;
        y += 26;
    }
    y += 14;
    for note in &spec.notes {
        for line in wrap(note, 38) {
            side.draw(&Text::new(line, (4, y), small.clone()))
                .map_err(chart_err)?;
            y += 16;
        }
    }
    Ok(())
}

/// Splits text into lines of at most `width` characters at spaces.
fn wrap(s: &str, width: usize) -> Vec<String> {
    let mut lines = Vec::new();
    let mut cur = String::new();
    for word in s.split_whitespace() {
        if !cur.is_empty() && cur.chars().count() + 1 + word.chars().count() > width {
            lines.push(std::mem::take(&mut cur));
        }
        if !cur.is_empty() {
            cur.push(' ');
        }
        cur.push_str(word);
    }
    if !cur.is_empty() {
        lines.push(cur);
    }
    lines
}

/// A backend that estimates text sizes from the character count instead of asking a font, and
/// forwards everything else (the SVG backend draws text without a font).
struct NaiveText<B>(B);

impl<B: DrawingBackend> DrawingBackend for NaiveText<B> {
    type ErrorType = B::ErrorType;

    fn get_size(&self) -> (u32, u32) {
        self.0.get_size()
    }

    fn ensure_prepared(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.ensure_prepared()
    }

    fn present(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.present()
    }

    fn draw_pixel(
        &mut self,
        point: BackendCoord,
        color: BackendColor,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.draw_pixel(point, color)
    }

    fn draw_line<S: BackendStyle>(
        &mut self,
        from: BackendCoord,
        to: BackendCoord,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.draw_line(from, to, style)
    }

    fn draw_rect<S: BackendStyle>(
        &mut self,
        upper_left: BackendCoord,
        bottom_right: BackendCoord,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.draw_rect(upper_left, bottom_right, style, fill)
    }

    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.draw_path(path, style)
    }

    fn draw_circle<S: BackendStyle>(
        &mut self,
        center: BackendCoord,
        radius: u32,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.draw_circle(center, radius, style, fill)
    }

    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.fill_polygon(vert, style)
    }

    fn draw_text<S: BackendTextStyle>(
        &mut self,
        text: &str,
        style: &S,
        pos: BackendCoord,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.draw_text(text, style, pos)
    }

    fn estimate_text_size<S: BackendTextStyle>(
        &self,
        text: &str,
        style: &S,
    ) -> Result<(u32, u32), DrawingErrorKind<Self::ErrorType>> {
        let size = style.size();
        Ok((
            (0.55 * size * text.chars().count() as f64).ceil() as u32,
            size.ceil() as u32,
        ))
    }

    fn blit_bitmap(
        &mut self,
        pos: BackendCoord,
        size: (u32, u32),
        src: &[u8],
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.blit_bitmap(pos, size, src)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pts() -> Vec<Point> {
        vec![
            Point {
                label: "puma560".into(),
                group: "tape".into(),
                x: 3e-6,
                y: 1e-14,
            },
            Point {
                label: "puma560".into(),
                group: "exact".into(),
                x: 2e-3,
                y: 0.0,
            },
        ]
    }

    #[test]
    fn svg_has_the_series_and_the_zero_error_note_without_a_font() {
        let spec = speed_accuracy(pts());
        assert!(spec.notes.iter().any(|n| n.contains("exactly 0")));
        let s = svg(&spec).unwrap();
        assert!(s.starts_with("<svg"));
        for needle in ["tape", "exact", "puma560", "Speed against accuracy"] {
            assert!(s.contains(needle), "{needle}");
        }
        let empty = svg(&scaling(vec![], vec![])).unwrap();
        assert!(empty.contains("Derivation time"));
    }

    #[test]
    fn wrap_keeps_words() {
        assert_eq!(wrap("aa bb cc", 5), vec!["aa bb", "cc"]);
        assert_eq!(wrap("", 5), Vec::<String>::new());
    }
}
