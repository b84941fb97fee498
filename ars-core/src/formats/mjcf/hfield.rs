//! `<asset><hfield>`: MuJoCo's height fields, read as MuJoCo's compiler reads them, and
//! made as a static triangle mesh of their grid.
//!
//! - `size="rx ry top base"`: the grid spans `[−rx, rx] × [−ry, ry]` in the geom's frame,
//!   its heights from 0 to `top` (MuJoCo's `base`, a box below the surface down to
//!   `−base`, is not made: the surface is collided from above).
//! - The heights: `elevation` (`nrow × ncol` numbers, the first row at `+y`), or a PNG
//!   `file` (grey levels, a colour picture's red ones, as MuJoCo reads them; the image's
//!   top row at `+y`), else all zero (MuJoCo's, for
//!   data set at run time, which ARS does not take). As MuJoCo does, they are scaled to
//!   `[0, 1]` (less their least, over their span) and kept in single precision, then
//!   times `top`.

use std::path::Path;

use nalgebra::Point3;

use super::defaults::Attrs;
use super::problem::{Parsed, problem};
use crate::scene::MAX_GRID_VERTICES;
use crate::shape::Shape;

/// An `<asset><hfield>` as read.
#[derive(Debug, PartialEq)]
pub(super) struct Hfield {
    /// Rows (along y) and columns (along x).
    pub(super) nrow: usize,
    pub(super) ncol: usize,
    /// `rx ry top base`.
    pub(super) size: [f64; 4],
    /// Heights in [0, 1], row-major, row 0 at `−ry`, column 0 at `−rx` (MuJoCo's
    /// `hfield_data`).
    pub(super) data: Vec<f64>,
}

impl Hfield {
    /// Its surface as a triangle mesh in the geom's frame, two triangles a cell facing +z.
    pub(super) fn shape(&self) -> Shape {
        let [rx, ry, top, _] = self.size;
        let (nrow, ncol) = (self.nrow, self.ncol);
        let step = |i: usize, n: usize, r: f64| -r + 2.0 * r * i as f64 / (n - 1) as f64;
        let mut vertices = Vec::with_capacity(nrow * ncol);
        for r in 0..nrow {
            for c in 0..ncol {
                vertices.push(Point3::new(step(c, ncol, rx), step(r, nrow, ry), self.data[r * ncol + c] * top));
            }
        }
        let index = |r: usize, c: usize| (r * ncol + c) as u32;
        let mut triangles = Vec::with_capacity(2 * (nrow - 1) * (ncol - 1));
        for r in 0..nrow - 1 {
            for c in 0..ncol - 1 {
                let (a, b, d, e) = (index(r, c), index(r, c + 1), index(r + 1, c), index(r + 1, c + 1));
                triangles.push([a, b, e]);
                triangles.push([a, e, d]);
            }
        }
        Shape::TriMesh { vertices, triangles }
    }
}

/// Reads an `<asset><hfield>` (its PNG file, if any, in `folder`): its name and what it is.
pub(super) fn hfield_asset(a: &Attrs<'_, '_>, folder: &Path) -> Parsed<(String, Hfield)> {
    let node = a.node;
    let size = a.fixed::<4>("size")?.ok_or_else(|| problem(&node, "needs a size (rx ry top base)"))?;
    if size[..3].iter().any(|s| !(s.is_finite() && *s > 0.0)) || !(size[3].is_finite() && size[3] >= 0.0) {
        return Err(problem(&node, format!("size {size:?} must be three positive numbers and a base of 0 or more")));
    }
    let count = |what: &str| -> Parsed<Option<usize>> {
        match a.number(what)? {
            None => Ok(None),
            Some(n) if n >= 2.0 && n.fract() == 0.0 && n <= MAX_GRID_VERTICES as f64 => Ok(Some(n as usize)),
            Some(n) => Err(problem(&node, format!("{what} {n} must be a whole number of at least 2"))),
        }
    };
    let (nrow, ncol) = (count("nrow")?, count("ncol")?);
    let (nrow, ncol, rows) = match (node.attribute("file"), nrow.zip(ncol)) {
        (Some(file), None) => {
            let (nrow, ncol, grey) = png_grey(&folder.join(file)).map_err(|e| problem(&node, e))?;
            (nrow, ncol, grey)
        }
        (Some(_), Some(_)) => return Err(problem(&node, "has both a file and nrow, ncol")),
        (None, Some((nrow, ncol))) => {
            if (nrow * ncol) as u64 > MAX_GRID_VERTICES {
                return Err(problem(&node, format!("{nrow} × {ncol} is more than {MAX_GRID_VERTICES} points")));
            }
            let rows = match a.numbers("elevation")? {
                Some(e) if e.len() == nrow * ncol => e,
                Some(e) => {
                    return Err(problem(
                        &node,
                        format!("elevation has {} numbers, nrow × ncol is {}", e.len(), nrow * ncol),
                    ));
                }
                None => vec![0.0; nrow * ncol],
            };
            (nrow, ncol, rows)
        }
        (None, None) => return Err(problem(&node, "needs a file, or nrow and ncol")),
    };
    if let Some(bad) = rows.iter().find(|v| !v.is_finite()) {
        return Err(problem(&node, format!("elevation {bad} is not finite")));
    }
    // The file's rows run from +y down; MuJoCo's data from −y up.
    let mut data: Vec<f64> = (0..nrow).rev().flat_map(|r| rows[r * ncol..(r + 1) * ncol].iter().copied()).collect();
    let (least, most) = data.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, m), v| (l.min(*v), m.max(*v)));
    let span = most - least;
    // In single precision, as MuJoCo keeps them (`hfield_data` is float).
    data.iter_mut().for_each(|v| *v = if span > 0.0 { f64::from(((*v - least) / span) as f32) } else { 0.0 });
    let name = match (node.attribute("name"), node.attribute("file")) {
        (Some(name), _) => name.to_string(),
        (None, Some(file)) => Path::new(file).file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default(),
        (None, None) => return Err(problem(&node, "an hfield without a file needs a name")),
    };
    Ok((name, Hfield { nrow, ncol, size, data }))
}

/// A PNG's grey levels (of a colour picture, its red levels), row-major from its top row:
/// `(rows, columns, levels)`.
fn png_grey(path: &Path) -> Result<(usize, usize, Vec<f64>), String> {
    let file = std::fs::File::open(path).map_err(|e| format!("cannot open {}: {e}", path.display()))?;
    let mut decoder = png::Decoder::new(std::io::BufReader::new(file));
    decoder.set_transformations(png::Transformations::EXPAND | png::Transformations::STRIP_16);
    let bad = |e: png::DecodingError| format!("{} is not a PNG ARS can read: {e}", path.display());
    let mut reader = decoder.read_info().map_err(bad)?;
    let (width, height) = (reader.info().width as usize, reader.info().height as usize);
    if width < 2 || height < 2 || (width * height) as u64 > MAX_GRID_VERTICES {
        return Err(format!(
            "{} is {width} × {height} pixels: at least 2 × 2, at most {MAX_GRID_VERTICES}",
            path.display()
        ));
    }
    let mut buffer = vec![0; reader.output_buffer_size().ok_or("the image is too large")?];
    let frame = reader.next_frame(&mut buffer).map_err(bad)?;
    let channels = frame.color_type.samples();
    let bytes = &buffer[..frame.buffer_size()];
    // The first channel: grey, or red (what MuJoCo 4.0 reads of a colour picture:
    // its heights equal the red levels of dm_control's deepmind.png to float precision).
    let grey = bytes.chunks(channels).map(|p| f64::from(p[0])).collect();
    Ok((height, width, grey))
}
