//! An SVG picture of the toolpath in the ZX plane: Z to the right, X up,
//! true to shape (the vertical scale is the radius), the X tick labels
//! giving diameters as the program writes them. Rapids dashed, feeds
//! solid, threads in their own colour.

use crate::interpolate::{Motion, SetPoint};
use alloc::string::String;
use alloc::vec::Vec;
use core::fmt::Write;

/// Points closer than this to the last kept one are dropped, mm.
const KEEP_MM: f64 = 0.02;

#[derive(Debug, Clone, Default)]
/// The XZ toolpath, collected period by period and drawn as SVG.
pub struct Plot {
    runs: Vec<(Motion, Vec<(f64, f64)>)>,
    /// The last set point, kept even when dropped, to end each run on it.
    last: Option<(Motion, (f64, f64))>,
}

impl Plot {
    /// An empty plot.
    pub fn new() -> Plot {
        Plot::default()
    }

    /// Accounts one period (work coordinates: what the program wrote).
    pub fn add(&mut self, p: &SetPoint) {
        let pt = (p.z, p.x * 0.5);
        let kind = p.motion;
        if kind == Motion::None {
            self.close();
            self.last = Some((kind, pt));
            return;
        }
        let open = matches!(self.runs.last(), Some((k, _)) if *k == kind)
            && !matches!(self.last, Some((Motion::None, _)));
        if !open {
            self.close();
            let start = self.last.map_or(pt, |(_, q)| q);
            self.runs.push((kind, alloc::vec![start]));
        }
        if let Some((_, pts)) = self.runs.last_mut() {
            let far = pts
                .last()
                .is_none_or(|q| libm::hypot(q.0 - pt.0, q.1 - pt.1) >= KEEP_MM);
            if far {
                pts.push(pt);
            }
        }
        self.last = Some((kind, pt));
    }

    /// Ends the open run on the last point seen.
    fn close(&mut self) {
        if let (Some((_, pts)), Some((_, q))) = (self.runs.last_mut(), self.last) {
            if pts.last() != Some(&q) {
                pts.push(q);
            }
        }
    }

    /// The SVG document.
    pub fn svg(&mut self, title: &str) -> String {
        self.close();
        let mut zmin = f64::INFINITY;
        let mut zmax = f64::NEG_INFINITY;
        let mut rmin = f64::INFINITY;
        let mut rmax = f64::NEG_INFINITY;
        for (_, pts) in &self.runs {
            for &(z, r) in pts {
                zmin = zmin.min(z);
                zmax = zmax.max(z);
                rmin = rmin.min(r);
                rmax = rmax.max(r);
            }
        }
        if !zmin.is_finite() {
            (zmin, zmax, rmin, rmax) = (-1.0, 1.0, -1.0, 1.0);
        }
        // Always show the spindle axis (X0) and a margin.
        rmin = rmin.min(0.0);
        rmax = rmax.max(0.0);
        let pad = 0.05 * (zmax - zmin).max(rmax - rmin).max(1.0);
        let (zmin, zmax, rmin, rmax) = (zmin - pad, zmax + pad, rmin - pad, rmax + pad);
        let (w_plot, h_max) = (900.0, 700.0);
        let mut scale = w_plot / (zmax - zmin);
        if (rmax - rmin) * scale > h_max {
            scale = h_max / (rmax - rmin);
        }
        let (ml, mt, mb, mr) = (70.0, 40.0, 50.0, 20.0);
        let w = (zmax - zmin) * scale + ml + mr;
        let h = (rmax - rmin) * scale + mt + mb;
        let sx = |z: f64| ml + (z - zmin) * scale;
        let sy = |r: f64| mt + (rmax - r) * scale;
        let mut s = String::new();
        let _ = writeln!(
            s,
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w:.0}\" height=\"{h:.0}\" viewBox=\"0 0 {w:.1} {h:.1}\" font-family=\"sans-serif\" font-size=\"12\">"
        );
        let _ = writeln!(s, "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>");
        let _ = writeln!(
            s,
            "<text x=\"{ml}\" y=\"20\" font-size=\"14\">{}</text>",
            escape(title)
        );
        // Grid and tick labels.
        let step_z = nice_step((zmax - zmin) / 8.0);
        let step_r = nice_step((rmax - rmin) / 6.0);
        let mut z = libm::ceil(zmin / step_z) * step_z;
        while z <= zmax {
            let x = sx(z);
            let _ = writeln!(
                s,
                "<line x1=\"{x:.2}\" y1=\"{:.2}\" x2=\"{x:.2}\" y2=\"{:.2}\" stroke=\"#e4e4e4\"/>",
                mt,
                h - mb
            );
            let _ = writeln!(
                s,
                "<text x=\"{x:.2}\" y=\"{:.2}\" text-anchor=\"middle\">{}</text>",
                h - mb + 16.0,
                label(z)
            );
            z += step_z;
        }
        let mut r = libm::ceil(rmin / step_r) * step_r;
        while r <= rmax {
            let y = sy(r);
            let _ = writeln!(
                s,
                "<line x1=\"{ml}\" y1=\"{y:.2}\" x2=\"{:.2}\" y2=\"{y:.2}\" stroke=\"#e4e4e4\"/>",
                w - mr
            );
            let _ = writeln!(
                s,
                "<text x=\"{:.2}\" y=\"{:.2}\" text-anchor=\"end\">{}</text>",
                ml - 6.0,
                y + 4.0,
                label(2.0 * r)
            );
            r += step_r;
        }
        let _ = writeln!(
            s,
            "<rect x=\"{ml}\" y=\"{mt}\" width=\"{:.2}\" height=\"{:.2}\" fill=\"none\" stroke=\"#888\"/>",
            w - ml - mr,
            h - mt - mb
        );
        // The spindle axis.
        let y0 = sy(0.0);
        let _ = writeln!(
            s,
            "<line x1=\"{ml}\" y1=\"{y0:.2}\" x2=\"{:.2}\" y2=\"{y0:.2}\" stroke=\"#999\" stroke-dasharray=\"12 3 2 3\"/>",
            w - mr
        );
        let _ = writeln!(
            s,
            "<text x=\"{:.2}\" y=\"{:.2}\" text-anchor=\"middle\">Z (mm)</text>",
            ml + (w - ml - mr) / 2.0,
            h - 12.0
        );
        let _ = writeln!(
            s,
            "<text x=\"16\" y=\"{:.2}\" transform=\"rotate(-90 16 {:.2})\" text-anchor=\"middle\">X (diameter, mm)</text>",
            mt + (h - mt - mb) / 2.0,
            mt + (h - mt - mb) / 2.0
        );
        for (kind, pts) in &self.runs {
            if pts.len() < 2 {
                continue;
            }
            let style = match kind {
                Motion::Rapid => "stroke=\"#d62728\" stroke-width=\"1\" stroke-dasharray=\"6 4\"",
                Motion::Thread => "stroke=\"#2ca02c\" stroke-width=\"1.6\"",
                _ => "stroke=\"#1f4e9c\" stroke-width=\"1.4\"",
            };
            s.push_str("<polyline fill=\"none\" ");
            s.push_str(style);
            s.push_str(" points=\"");
            for &(z, r) in pts {
                let _ = write!(s, "{:.2},{:.2} ", sx(z), sy(r));
            }
            s.push_str("\"/>\n");
        }
        // Legend, in the top margin right of the title.
        let items = [
            ("rapid", "#d62728", "6 4"),
            ("feed", "#1f4e9c", ""),
            ("thread", "#2ca02c", ""),
        ];
        for (i, (name, colour, dash)) in items.iter().enumerate() {
            let lx = w - mr - 240.0 + 80.0 * i as f64;
            let y = 20.0;
            let _ = writeln!(
                s,
                "<line x1=\"{lx:.1}\" y1=\"{:.1}\" x2=\"{:.1}\" y2=\"{:.1}\" stroke=\"{colour}\" stroke-width=\"1.6\" stroke-dasharray=\"{dash}\"/><text x=\"{:.1}\" y=\"{y:.1}\">{name}</text>",
                y - 4.0,
                lx + 26.0,
                y - 4.0,
                lx + 32.0,
            );
        }
        s.push_str("</svg>\n");
        s
    }
}

/// 1, 2 or 5 × 10ⁿ at or above `raw`.
fn nice_step(raw: f64) -> f64 {
    let raw = if raw > 0.0 && raw.is_finite() {
        raw
    } else {
        1.0
    };
    let p = libm::pow(10.0, libm::floor(libm::log10(raw)));
    for m in [1.0, 2.0, 5.0, 10.0] {
        if m * p >= raw {
            return m * p;
        }
    }
    10.0 * p
}

fn label(v: f64) -> String {
    let mut s = String::new();
    let v = if v.abs() < 1e-9 { 0.0 } else { v };
    let _ = write!(s, "{}", libm::round(v * 1000.0) / 1000.0);
    s
}

fn escape(t: &str) -> String {
    let mut s = String::new();
    for c in t.chars() {
        match c {
            '<' => s.push_str("&lt;"),
            '>' => s.push_str("&gt;"),
            '&' => s.push_str("&amp;"),
            '"' => s.push_str("&quot;"),
            c => s.push(c),
        }
    }
    s
}
