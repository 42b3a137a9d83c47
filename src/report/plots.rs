//! Line and scatter charts as SVG text, drawn with the `plotters` SVG backend (no system fonts:
//! labels are SVG `<text>` elements, the viewer picks the font).

use plotters::prelude::*;

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Style {
    /// Solid line.
    Line,
    /// Thin dashed-looking line (drawn lighter), e.g. hole wall.
    Thin,
    /// Point markers.
    Points,
    /// Line with point markers.
    LinePoints,
}

/// One named series of (x, y) points in display units.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend name (also searched for by tests).
    pub name: String,
    /// Points in display units.
    pub points: Vec<(f64, f64)>,
    /// Drawing style.
    pub style: Style,
    /// Colour index into the palette.
    pub color: usize,
}

impl Series {
    /// A series from name, points, style and colour index.
    pub fn new(name: &str, points: Vec<(f64, f64)>, style: Style, color: usize) -> Series {
        Series {
            name: name.to_string(),
            points,
            style,
            color,
        }
    }
}

/// Shaded spans of x over the full height of the plot (e.g. buckled MD intervals), with one
/// legend entry; nothing is drawn or listed when there is no span.
#[derive(Debug, Clone)]
pub struct Band {
    /// Legend name.
    pub name: String,
    /// (from, to) x intervals in display units.
    pub spans: Vec<(f64, f64)>,
    /// Colour index into the palette.
    pub color: usize,
}

/// A chart: title, axis labels and series.
#[derive(Debug, Clone)]
pub struct Chart {
    /// Caption.
    pub title: String,
    /// X axis label with unit.
    pub x_label: String,
    /// Y axis label with unit.
    pub y_label: String,
    /// Series (several series of one name share one legend entry, e.g. a curve with gaps).
    pub series: Vec<Series>,
    /// Shaded x intervals drawn under the series.
    pub bands: Vec<Band>,
    /// Same scale on both axes (plan view, vertical section).
    pub equal_aspect: bool,
    /// Y axis pointing down (depth).
    pub y_down: bool,
    /// Horizontal line at y = 0.
    pub zero_line: bool,
    /// Size in pixels (width, height).
    pub size: (u32, u32),
}

impl Chart {
    /// A chart with default size (860 x 340), no equal aspect, y up.
    pub fn new(title: &str, x_label: &str, y_label: &str) -> Chart {
        Chart {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            series: Vec::new(),
            bands: Vec::new(),
            equal_aspect: false,
            y_down: false,
            zero_line: false,
            size: (860, 340),
        }
    }
    /// Add a series.
    pub fn with(mut self, s: Series) -> Chart {
        self.series.push(s);
        self
    }
    /// Add a band of shaded x intervals.
    pub fn with_band(mut self, b: Band) -> Chart {
        self.bands.push(b);
        self
    }
}

/// Names of the legend entries of `chart`, in drawing order: bands with spans, then series with
/// points, each name once.
pub fn legend_names(chart: &Chart) -> Vec<&str> {
    let mut names: Vec<&str> = Vec::new();
    let bands = chart
        .bands
        .iter()
        .filter(|b| !b.spans.is_empty())
        .map(|b| b.name.as_str());
    let series = chart
        .series
        .iter()
        .filter(|s| !s.points.is_empty())
        .map(|s| s.name.as_str());
    for n in bands.chain(series) {
        if !names.contains(&n) {
            names.push(n);
        }
    }
    names
}

/// The corner of the plotting area where the legend covers the fewest drawn points: the series
/// are sampled along their lines (about 200 samples across the plot) and counted inside the
/// legend's box (estimated from its entries) at each corner. Ties go to upper right, upper
/// left, lower right, lower left in that order. `x`, `y`: the axis ranges; `plot_px`: the size
/// of the plotting area in pixels.
pub fn legend_corner(chart: &Chart, x: (f64, f64), y: (f64, f64), plot_px: (f64, f64)) -> SeriesLabelPosition {
    let names = legend_names(chart);
    let longest = names.iter().map(|n| n.chars().count()).max().unwrap_or(0) as f64;
    // plotters' legend: 12 px font, about 7 px per character, the mark, margins; 20 px per entry
    let w = ((longest * 7.0 + 50.0) / plot_px.0).min(1.0);
    let h = ((names.len() as f64 * 20.0 + 14.0) / plot_px.1).min(1.0);
    let norm = |p: (f64, f64)| {
        let u = (p.0 - x.0) / (x.1 - x.0);
        let v = (p.1 - y.0) / (y.1 - y.0);
        (u, if chart.y_down { 1.0 - v } else { v })
    };
    let mut samples: Vec<(f64, f64)> = Vec::new();
    for s in chart.series.iter().filter(|s| !s.points.is_empty()) {
        let pts: Vec<(f64, f64)> = s.points.iter().map(|&p| norm(p)).collect();
        samples.push(pts[0]);
        if s.style == Style::Points {
            samples.extend(&pts[1..]);
            continue;
        }
        for win in pts.windows(2) {
            let (a, b) = (win[0], win[1]);
            let n = ((b.0 - a.0).hypot(b.1 - a.1) * 200.0).ceil().clamp(1.0, 400.0) as usize;
            samples.extend((1..=n).map(|k| {
                let t = k as f64 / n as f64;
                (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1))
            }));
        }
    }
    let corners = [
        (SeriesLabelPosition::UpperRight, (1.0 - w, 1.0), (1.0 - h, 1.0)),
        (SeriesLabelPosition::UpperLeft, (0.0, w), (1.0 - h, 1.0)),
        (SeriesLabelPosition::LowerRight, (1.0 - w, 1.0), (0.0, h)),
        (SeriesLabelPosition::LowerLeft, (0.0, w), (0.0, h)),
    ];
    let covered = |(u0, u1): (f64, f64), (v0, v1): (f64, f64)| {
        samples
            .iter()
            .filter(|p| p.0 >= u0 && p.0 <= u1 && p.1 >= v0 && p.1 <= v1)
            .count()
    };
    let mut best = (usize::MAX, SeriesLabelPosition::UpperRight);
    for (pos, u, v) in corners {
        let n = covered(u, v);
        if n < best.0 {
            best = (n, pos);
        }
    }
    best.1
}

/// Palette (colour-blind friendly, Okabe-Ito).
pub const PALETTE: [RGBColor; 8] = [
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(0, 0, 0),
    RGBColor(120, 120, 120),
];

fn range(vals: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for v in vals {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() {
        return None;
    }
    let span = hi - lo;
    let pad = if span > 0.0 {
        0.05 * span
    } else {
        lo.abs().max(1.0) * 0.05
    };
    Some((lo - pad, hi + pad))
}

/// Render `chart` to SVG text. Fails (message) on a non-finite value or when no series has points.
pub fn render(chart: &Chart) -> Result<String, String> {
    for s in &chart.series {
        if let Some(p) = s.points.iter().find(|p| !(p.0.is_finite() && p.1.is_finite())) {
            return Err(format!(
                "chart `{}`, series `{}`: non-finite point ({}, {})",
                chart.title, s.name, p.0, p.1
            ));
        }
    }
    let all = || chart.series.iter().flat_map(|s| s.points.iter());
    let (mut x0, mut x1) = range(all().map(|p| p.0)).ok_or_else(|| format!("chart `{}`: no data", chart.title))?;
    let (mut y0, mut y1) = range(all().map(|p| p.1)).ok_or_else(|| format!("chart `{}`: no data", chart.title))?;
    if chart.zero_line {
        y0 = y0.min(0.0);
        y1 = y1.max(0.0);
    }
    let (w, h) = chart.size;
    let (plot_w, plot_h) = (w as f64 - 110.0, h as f64 - 100.0);
    if chart.equal_aspect {
        // widen the tighter axis so one unit spans the same pixels on both
        let sx = (x1 - x0) / plot_w;
        let sy = (y1 - y0) / plot_h;
        if sx > sy {
            let c = 0.5 * (y0 + y1);
            y0 = c - 0.5 * sx * plot_h;
            y1 = c + 0.5 * sx * plot_h;
        } else {
            let c = 0.5 * (x0 + x1);
            x0 = c - 0.5 * sy * plot_w;
            x1 = c + 0.5 * sy * plot_w;
        }
    }
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (w, h)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let yr = if chart.y_down { (y1, y0) } else { (y0, y1) };
        let mut ctx = ChartBuilder::on(&root)
            .caption(&chart.title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(64)
            .build_cartesian_2d(x0..x1, yr.0..yr.1)
            .map_err(|e| e.to_string())?;
        ctx.configure_mesh()
            .x_desc(chart.x_label.as_str())
            .y_desc(chart.y_label.as_str())
            .light_line_style(RGBColor(235, 235, 235))
            .label_style(("sans-serif", 12))
            .draw()
            .map_err(|e| e.to_string())?;
        for b in chart.bands.iter().filter(|b| !b.spans.is_empty()) {
            let c = PALETTE[b.color % PALETTE.len()];
            ctx.draw_series(
                b.spans
                    .iter()
                    .map(|&(a, e)| Rectangle::new([(a, y0), (e, y1)], c.mix(0.22).filled())),
            )
            .map_err(|e| e.to_string())?
            .label(b.name.as_str())
            .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 18, y + 5)], c.mix(0.35).filled()));
        }
        if chart.zero_line {
            ctx.draw_series(LineSeries::new(vec![(x0, 0.0), (x1, 0.0)], BLACK.mix(0.4)))
                .map_err(|e| e.to_string())?;
        }
        let mut listed: Vec<&str> = Vec::new();
        for s in chart.series.iter().filter(|s| !s.points.is_empty()) {
            let c = PALETTE[s.color % PALETTE.len()];
            let pts = s.points.clone();
            let anno = match s.style {
                Style::Line => ctx.draw_series(LineSeries::new(pts, c.stroke_width(2))),
                Style::Thin => ctx.draw_series(LineSeries::new(pts, c.mix(0.8).stroke_width(1))),
                Style::Points => ctx.draw_series(pts.into_iter().map(|p| Circle::new(p, 3, c.filled()))),
                Style::LinePoints => {
                    ctx.draw_series(LineSeries::new(pts.clone(), c.stroke_width(1)))
                        .map_err(|e| e.to_string())?;
                    ctx.draw_series(pts.into_iter().map(|p| Circle::new(p, 3, c.filled())))
                }
            }
            .map_err(|e| e.to_string())?;
            if !listed.contains(&s.name.as_str()) {
                listed.push(s.name.as_str());
                anno.label(s.name.as_str())
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], c.stroke_width(2)));
            }
        }
        ctx.configure_series_labels()
            .position(legend_corner(chart, (x0, x1), (y0, y1), (plot_w, plot_h)))
            .border_style(BLACK.mix(0.3))
            .background_style(WHITE.mix(0.85))
            .label_font(("sans-serif", 12))
            .draw()
            .map_err(|e| e.to_string())?;
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(svg)
}

/// A filled rectangle in data coordinates, for schematics.
#[derive(Debug, Clone, Copy)]
pub struct Block {
    /// Lower-left corner (x, y).
    pub from: (f64, f64),
    /// Upper-right corner (x, y).
    pub to: (f64, f64),
    /// Colour index.
    pub color: usize,
}

/// Render rectangles (and optional outline series) on axes, e.g. a BHA schematic.
pub fn render_blocks(chart: &Chart, blocks: &[Block]) -> Result<String, String> {
    let mut pts: Vec<(f64, f64)> = blocks.iter().flat_map(|b| [b.from, b.to]).collect();
    pts.extend(chart.series.iter().flat_map(|s| s.points.iter().copied()));
    if let Some(p) = pts.iter().find(|p| !(p.0.is_finite() && p.1.is_finite())) {
        return Err(format!("chart `{}`: non-finite point ({}, {})", chart.title, p.0, p.1));
    }
    let (x0, x1) = range(pts.iter().map(|p| p.0)).ok_or_else(|| format!("chart `{}`: no data", chart.title))?;
    let (y0, y1) = range(pts.iter().map(|p| p.1)).ok_or_else(|| format!("chart `{}`: no data", chart.title))?;
    let (w, h) = chart.size;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (w, h)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let mut ctx = ChartBuilder::on(&root)
            .caption(&chart.title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(64)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|e| e.to_string())?;
        ctx.configure_mesh()
            .x_desc(chart.x_label.as_str())
            .y_desc(chart.y_label.as_str())
            .disable_y_mesh()
            .label_style(("sans-serif", 12))
            .draw()
            .map_err(|e| e.to_string())?;
        ctx.draw_series(blocks.iter().map(|b| {
            let c = PALETTE[b.color % PALETTE.len()];
            Rectangle::new([b.from, b.to], c.mix(0.75).filled())
        }))
        .map_err(|e| e.to_string())?;
        ctx.draw_series(
            blocks
                .iter()
                .map(|b| Rectangle::new([b.from, b.to], BLACK.mix(0.6).stroke_width(1))),
        )
        .map_err(|e| e.to_string())?;
        for s in &chart.series {
            let c = PALETTE[s.color % PALETTE.len()];
            ctx.draw_series(LineSeries::new(s.points.clone(), c.stroke_width(1)))
                .map_err(|e| e.to_string())?
                .label(s.name.as_str())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], c.stroke_width(2)));
        }
        if !chart.series.is_empty() {
            ctx.configure_series_labels()
                .position(SeriesLabelPosition::UpperRight)
                .border_style(BLACK.mix(0.3))
                .background_style(WHITE.mix(0.85))
                .label_font(("sans-serif", 12))
                .draw()
                .map_err(|e| e.to_string())?;
        }
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(svg)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn non_finite_points_are_an_error_not_a_plot() {
        let c = Chart::new("t", "x", "y").with(Series::new("s", vec![(0.0, 1.0), (1.0, f64::NAN)], Style::Line, 0));
        assert!(render(&c).unwrap_err().contains("non-finite"));
        let empty = Chart::new("t", "x", "y");
        assert!(render(&empty).is_err());
    }

    /// Reference: by construction, a rising line leaves the upper-left and lower-right corners
    /// empty, a falling one the upper-right; the legend goes to the first empty corner.
    #[test]
    fn legend_goes_to_an_empty_corner() {
        let line = |pts: Vec<(f64, f64)>| Chart::new("t", "x", "y").with(Series::new("curve", pts, Style::Line, 0));
        let size = (750.0, 240.0);
        let rising = line(vec![(0.0, 0.0), (10.0, 10.0)]);
        let pos = legend_corner(&rising, (0.0, 10.0), (0.0, 10.0), size);
        assert!(matches!(pos, SeriesLabelPosition::UpperLeft), "{pos:?}");
        let falling = line(vec![(0.0, 10.0), (10.0, 0.0)]);
        let pos = legend_corner(&falling, (0.0, 10.0), (0.0, 10.0), size);
        assert!(matches!(pos, SeriesLabelPosition::UpperRight), "{pos:?}");
        // y pointing down flips the picture: the rising data line falls on screen
        let mut down = rising.clone();
        down.y_down = true;
        let pos = legend_corner(&down, (0.0, 10.0), (0.0, 10.0), size);
        assert!(matches!(pos, SeriesLabelPosition::UpperRight), "{pos:?}");
        // a line along the top edge and one up the left edge: the lower right is free
        let edge = line(vec![(0.0, 0.0), (0.0, 10.0), (10.0, 10.0)]);
        let pos = legend_corner(&edge, (0.0, 10.0), (0.0, 10.0), size);
        assert!(matches!(pos, SeriesLabelPosition::LowerRight), "{pos:?}");
    }

    /// Reference: a series split in two (a curve with a gap) has one legend entry; a band with
    /// spans adds one, an empty band none.
    #[test]
    fn legend_names_are_listed_once() {
        let c = Chart::new("t", "x", "y")
            .with(Series::new("onset", vec![(0.0, 1.0), (1.0, 1.0)], Style::Thin, 0))
            .with(Series::new("onset", vec![(2.0, 1.0), (3.0, 1.0)], Style::Thin, 0))
            .with_band(Band {
                name: "buckled".into(),
                spans: vec![(0.5, 1.5)],
                color: 1,
            })
            .with_band(Band {
                name: "helical".into(),
                spans: vec![],
                color: 2,
            });
        assert_eq!(legend_names(&c), vec!["buckled", "onset"]);
        let svg = render(&c).unwrap();
        assert_eq!(svg.matches("\nonset\n").count(), 1);
        assert_eq!(svg.matches("\nbuckled\n").count(), 1);
        assert!(!svg.contains("helical"));
    }

    #[test]
    fn a_chart_holds_its_series_name_and_one_polyline_per_line_series() {
        let c = Chart::new("t", "x", "y")
            .with(Series::new("first", vec![(0.0, 1.0), (1.0, 2.0)], Style::Line, 0))
            .with(Series::new("second", vec![(0.0, 0.0), (1.0, 3.0)], Style::Line, 1));
        let svg = render(&c).unwrap();
        // plotters writes each label on its own line inside <text>
        assert!(svg.contains("\nfirst\n") && svg.contains("\nsecond\n"));
        // each series: its data line and its legend mark, in its palette colour
        let lines = |colour: &str| {
            svg.lines()
                .filter(|l| l.starts_with("<polyline") && l.contains(&format!("stroke=\"{colour}\"")))
                .count()
        };
        assert_eq!(lines("#0072B2"), 2);
        assert_eq!(lines("#D55E00"), 2);
    }
}
