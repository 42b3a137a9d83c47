//! Outputs of `drillpath tendency` (docs/guide.md "Tendency charts"): the build/turn rate
//! table (`tendency.csv`), the chart (`tendency.svg`: dogleg capability against the tool's
//! setting for each WOB, rotary tendency against inclination for each WOB) and the stdout
//! summary.

use super::num;
use super::plots::{render, Chart, Series, Style};
use crate::predict::tendency::{Sweep, TendencyPoint};

/// Degrees per 30 m of a curvature in rad/m.
fn deg30(k: f64) -> f64 {
    k.to_degrees() * 30.0
}

/// Header of `tendency.csv`.
pub const TENDENCY_HEADER: &str =
    "sweep,bend_deg,ratio,wob_kN,inc_deg,mode,toolface_deg,build_deg_per_30m,right_deg_per_30m,dogleg_deg_per_30m,note,pad_od_in,pad_under_gauge_in";

/// `tendency.csv`: one row per point (the rates empty and the reason in `note` where the steady
/// dogleg was not found; `bend_deg` empty for an RSS, `ratio` for a bent housing; the pad
/// columns, in inches, empty without a pad stabilizer below the bend).
pub fn tendency_csv(points: &[TendencyPoint]) -> Result<String, String> {
    let mut out = String::from(TENDENCY_HEADER);
    out.push('\n');
    for p in points {
        let opt = |v: Option<f64>, d: usize| v.map(|x| num(x, d)).transpose().map(|x| x.unwrap_or_default());
        let (rates, note) = match &p.turn {
            Ok(t) => (
                [
                    num(deg30(t.build_rad_per_m), 4)?,
                    num(deg30(t.right_rad_per_m), 4)?,
                    num(deg30(t.dogleg_rad_per_m()), 4)?,
                ]
                .join(","),
                String::new(),
            ),
            Err(e) => (",,".to_string(), format!("\"{}\"", e.replace('"', "'"))),
        };
        let inch = |v: Option<f64>| opt(v.map(|x| x / 0.0254), 4);
        out.push_str(&format!(
            "{},{},{},{},{},{},{},{rates},{note},{},{}\n",
            p.sweep.name(),
            opt(p.bend_rad.map(f64::to_degrees), 3)?,
            opt(p.ratio, 3)?,
            num(p.wob_n / 1e3, 2)?,
            num(p.inc_rad.to_degrees(), 2)?,
            if p.rotating { "rotate" } else { "slide" },
            num(p.toolface_rad.to_degrees(), 2)?,
            inch(p.pad_od_m)?,
            inch(p.pad_under_gauge_m)?,
        ));
    }
    Ok(out)
}

/// The x of a capability point: its bend angle (deg) or its ratio.
fn setting(p: &TendencyPoint) -> f64 {
    p.bend_rad.map(f64::to_degrees).or(p.ratio).unwrap_or(0.0)
}

/// The lines of `sweep`'s points: the distinct (WOB N, pad under-gauge m) in the points' order.
fn lines(points: &[TendencyPoint], sweep: Sweep) -> Vec<(f64, Option<f64>)> {
    let mut out: Vec<(f64, Option<f64>)> = Vec::new();
    for p in points.iter().filter(|p| p.sweep == sweep) {
        if !out.iter().any(|l| on_line(p, l)) {
            out.push((p.wob_n, p.pad_under_gauge_m));
        }
    }
    out
}

/// True when `p` is on the line (WOB, pad under-gauge) `l`.
fn on_line(p: &TendencyPoint, l: &(f64, Option<f64>)) -> bool {
    let pad = match (p.pad_under_gauge_m, l.1) {
        (Some(a), Some(b)) => (a - b).abs() < 1e-9,
        (a, b) => a.is_none() && b.is_none(),
    };
    (p.wob_n - l.0).abs() < 1e-6 && pad
}

/// The name of a line: its WOB, and its pad's under-gauge when `pads` (more than one in the
/// sweep).
fn line_name(l: &(f64, Option<f64>), pads: bool) -> String {
    let wob = format!("WOB {:.0} kN", l.0 / 1e3);
    match l.1 {
        Some(u) if pads && u.abs() < 1e-9 => format!("{wob}, pad full gauge"),
        Some(u) if pads => format!("{wob}, pad {} in under gauge", crate::units::message_number(u / 0.0254)),
        _ => wob,
    }
}

/// The series of `sweep`'s points, one per line of [`lines`]: (x of a point, y of its steady
/// turn). With several pads, a pad's lines share a colour and each WOB has its style.
fn per_wob(
    points: &[TendencyPoint],
    sweep: Sweep,
    x: fn(&TendencyPoint) -> f64,
    y: fn(f64, f64) -> f64,
    label: &str,
) -> Vec<Series> {
    let ls = lines(points, sweep);
    let mut pads: Vec<Option<f64>> = Vec::new();
    let mut wobs: Vec<f64> = Vec::new();
    for l in &ls {
        if !pads.iter().any(|p| {
            p.zip(l.1)
                .map_or(p.is_none() && l.1.is_none(), |(a, b)| (a - b).abs() < 1e-9)
        }) {
            pads.push(l.1);
        }
        if !wobs.iter().any(|w| (w - l.0).abs() < 1e-6) {
            wobs.push(l.0);
        }
    }
    let several = pads.len() > 1;
    ls.iter()
        .enumerate()
        .map(|(k, l)| {
            let pts = points
                .iter()
                .filter(|p| p.sweep == sweep && on_line(p, l))
                .filter_map(|p| {
                    p.turn
                        .as_ref()
                        .ok()
                        .map(|t| (x(p), y(deg30(t.build_rad_per_m), deg30(t.right_rad_per_m))))
                })
                .collect();
            let (style, color) = if several {
                let w = wobs.iter().position(|w| (w - l.0).abs() < 1e-6).unwrap_or(0);
                let styles = [Style::Thin, Style::Line, Style::LinePoints, Style::Points];
                let c = pads.iter().position(|p| *p == l.1).unwrap_or(0);
                (styles[w % styles.len()], c)
            } else {
                (Style::LinePoints, k)
            };
            Series::new(&format!("{label}{}", line_name(l, several)), pts, style, color)
        })
        .collect()
}

/// `tendency.svg`: the capability chart (dogleg against the bend angle or the ratio, one line
/// per WOB) above the rotary chart (build and right-turn rates against the inclination, one
/// line each per WOB), two charts stacked in one SVG.
pub fn tendency_svg(points: &[TendencyPoint], rss: bool) -> Result<String, String> {
    let (what, x_label) = if rss {
        (
            "RSS dogleg capability (rotating, steering at the toolface)",
            "steering ratio (-)",
        )
    } else {
        ("Motor yield (sliding at the toolface)", "bend angle (deg)")
    };
    let mut cap = Chart::new(what, x_label, "dogleg (deg/30 m)");
    for s in per_wob(points, Sweep::Capability, setting, |b, r| b.hypot(r), "") {
        cap = cap.with(s);
    }
    let mut rot = Chart::new(
        if rss {
            "Rotary tendency (RSS neutral)"
        } else {
            "Rotary tendency (bent housing rotating)"
        },
        "inclination (deg)",
        "rate (deg/30 m)",
    );
    rot.zero_line = true;
    let n = per_wob(points, Sweep::Rotary, |p| p.inc_rad.to_degrees(), |b, _| b, "build, ");
    let m = n.len();
    for s in n {
        rot = rot.with(s);
    }
    for mut s in per_wob(points, Sweep::Rotary, |p| p.inc_rad.to_degrees(), |_, r| r, "right, ") {
        s.color += m;
        s.style = Style::Points;
        rot = rot.with(s);
    }
    let strip = |svg: String| -> String {
        match svg.find("<svg") {
            Some(i) => svg[i..].to_string(),
            None => svg,
        }
    };
    let (a, b) = (strip(render(&cap)?), strip(render(&rot)?));
    let (w, h1, h2) = (cap.size.0, cap.size.1, rot.size.1);
    Ok(format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{}\">\n<g>{}</g>\n<g transform=\"translate(0,{h1})\">{}</g>\n</svg>\n",
        h1 + h2,
        a,
        b
    ))
}

/// The stdout summary: one line per WOB of each sweep (the dogleg per setting, the rotary build
/// and right per inclination, deg/30 m; `-` where not found) and the count of points not found.
pub fn tendency_text(points: &[TendencyPoint], rss: bool) -> String {
    let mut out = String::new();
    let fmt = |v: Option<f64>| v.map(|x| format!("{x:+.2}")).unwrap_or_else(|| "-".into());
    for sweep in [Sweep::Capability, Sweep::Rotary] {
        let ps: Vec<&TendencyPoint> = points.iter().filter(|p| p.sweep == sweep).collect();
        let ls = lines(points, sweep);
        let pads = sweep == Sweep::Capability && ls.iter().any(|l| l.1.is_some());
        for l in ls {
            let cells: Vec<String> = ps
                .iter()
                .filter(|p| on_line(p, &l))
                .map(|p| {
                    let t = p.turn.as_ref().ok();
                    match sweep {
                        Sweep::Capability => format!(
                            "{}{}: {}",
                            if rss { "ratio " } else { "" },
                            if rss {
                                format!("{:.2}", setting(p))
                            } else {
                                format!("{:.2} deg", setting(p))
                            },
                            fmt(t.map(|t| deg30(t.dogleg_rad_per_m())))
                        ),
                        Sweep::Rotary => format!(
                            "{:.0} deg: {}/{}",
                            p.inc_rad.to_degrees(),
                            fmt(t.map(|t| deg30(t.build_rad_per_m))),
                            fmt(t.map(|t| deg30(t.right_rad_per_m)))
                        ),
                    }
                })
                .collect();
            let head = match sweep {
                Sweep::Capability if rss => "RSS dogleg capability",
                Sweep::Capability => "motor yield sliding",
                Sweep::Rotary => "rotary build/right",
            };
            out.push_str(&format!(
                "  {head} at {} (deg/30 m): {}\n",
                line_name(&l, pads),
                cells.join(", ")
            ));
        }
    }
    let failed = points.iter().filter(|p| p.turn.is_err()).count();
    if failed > 0 {
        out.push_str(&format!(
            "  {failed} of {} points without a steady dogleg (reasons in tendency.csv, `note`)\n",
            points.len()
        ));
    }
    out
}
