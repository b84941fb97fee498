//! Line charts as 800×600 PNG files, with axis labels (quantity and unit) and a legend.
//!
//! plotters draws into a buffer with the DejaVu Sans font read from the system
//! (Debian's `fonts-dejavu-core`); the `image` crate writes the PNG. (plotters' own
//! PNG encoder and font lookup built a second `image` crate and font-kit with
//! FreeType and Fontconfig: a cold build's time for nothing the viewer lacks.)

use std::error::Error;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use plotters::prelude::*;

/// Where Debian and other Linux systems keep DejaVu Sans.
const FONT_PATHS: [&str; 3] = [
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/TTF/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu/DejaVuSans.ttf",
];

const SIZE: (u32, u32) = (800, 600);

/// Registers DejaVu Sans as plotters' "sans-serif" (once).
fn register_font() -> Result<(), Box<dyn Error>> {
    static REGISTERED: OnceLock<Result<(), String>> = OnceLock::new();
    let registered = REGISTERED.get_or_init(|| {
        let bytes = FONT_PATHS.iter().find_map(|p| std::fs::read(p).ok()).ok_or_else(|| {
            format!(
                "no DejaVu Sans font for the plots (looked in {}): install fonts-dejavu-core",
                FONT_PATHS.join(", ")
            )
        })?;
        // plotters keeps the font for the whole process.
        let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
        plotters::style::register_font("sans-serif", FontStyle::Normal, bytes)
            .map_err(|_| "DejaVu Sans could not be read as a font".to_string())
    });
    registered.clone().map_err(Into::into)
}

/// One curve.
pub struct Series {
    /// Legend entry.
    pub label: String,
    /// `(x, y)` points.
    pub points: Vec<(f64, f64)>,
}

impl Series {
    /// A curve from its label and points.
    pub fn new(label: &str, points: Vec<(f64, f64)>) -> Self {
        Series { label: label.to_string(), points }
    }
}

const COLORS: [RGBColor; 5] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
];

fn range(values: impl Iterator<Item = f64> + Clone) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let pad = if hi > lo { 0.05 * (hi - lo) } else { lo.abs().max(1.0) * 0.05 };
    (lo - pad, hi + pad)
}

/// Draws `series` into `dir/file` and returns the path.
pub fn line_chart(
    dir: &Path,
    file: &str,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
) -> Result<PathBuf, Box<dyn Error>> {
    std::fs::create_dir_all(dir)?;
    register_font()?;
    let path = dir.join(file);
    let mut pixels = vec![0u8; (SIZE.0 * SIZE.1 * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut pixels, SIZE).into_drawing_area();
        root.fill(&WHITE)?;
        let all = series.iter().flat_map(|s| s.points.iter());
        let (x0, x1) = range(all.clone().map(|p| p.0));
        let (y0, y1) = range(all.map(|p| p.1));
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 24))
            .margin(15)
            .x_label_area_size(50)
            .y_label_area_size(80)
            .build_cartesian_2d(x0..x1, y0..y1)?;
        chart
            .configure_mesh()
            .x_desc(x_label)
            .y_desc(y_label)
            .axis_desc_style(("sans-serif", 18))
            .label_style(("sans-serif", 15))
            .draw()?;
        for (i, s) in series.iter().enumerate() {
            let color = COLORS[i % COLORS.len()];
            chart
                .draw_series(LineSeries::new(s.points.iter().copied(), color.stroke_width(1)))?
                .label(s.label.clone())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2)));
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 16))
            .draw()?;
        root.present()?;
    }
    image::save_buffer(&path, &pixels, SIZE.0, SIZE.1, image::ExtendedColorType::Rgb8)?;
    eprintln!("wrote {}", path.display());
    Ok(path)
}

/// `(time, f(record))` for every sample.
pub fn over_time<R>(samples: &[ars::Sample<R>], f: impl Fn(&R) -> f64) -> Vec<(f64, f64)> {
    samples.iter().map(|s| (s.time, f(&s.record))).collect()
}

/// Removes the 2π jumps of an angle that ODE reports in (−π, π], so that a joint
/// turning past ±π plots as one continuous curve.
pub fn unwrapped(points: Vec<(f64, f64)>) -> Vec<(f64, f64)> {
    use std::f64::consts::{PI, TAU};
    let mut out: Vec<(f64, f64)> = Vec::with_capacity(points.len());
    for (x, a) in points {
        let a = match out.last() {
            Some(&(_, prev)) => prev + (a - prev + PI).rem_euclid(TAU) - PI,
            None => a,
        };
        out.push((x, a));
    }
    out
}
