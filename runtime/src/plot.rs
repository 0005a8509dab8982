//! An SVG picture of the toolpath in the ZX plane: Z to the right, X up,
//! true to shape (the vertical scale is the radius), the X tick labels
//! giving diameters as the program writes them. Rapids dashed, feeds
//! solid, threads in their own colour.
//!
//! The frame is fitted to the cutting moves (feeds and threads), the stock
//! and the spindle axis, not to the rapids: a rapid to the tool-change
//! point or a reference return leaves the frame, clipped at its edge with
//! an arrow, instead of shrinking the part to a speck. The start point
//! and each tool change are marked (with the tool number); a marker
//! outside the frame is pinned to its edge. Paths are simplified to a
//! tenth of a pixel ([`crate::simplify`]).

use crate::interpolate::{Motion, SetPoint};
use crate::simplify::simplify;
use alloc::string::String;
use alloc::vec::Vec;
use core::fmt::Write;

/// Points closer than this to the last kept one are dropped as they come,
/// mm (finer than the 0.001 mm resolution would not show; this bounds the
/// memory of a long run before the simplification at the end).
const KEEP_MM: f64 = 0.005;
/// The simplification tolerance, pixels.
const TOLERANCE_PX: f64 = 0.1;
/// The drawing area's largest width and height, pixels.
const MAX_W: f64 = 900.0;
const MAX_H: f64 = 700.0;
/// Margins: left (X labels), top (title and legend), right, bottom.
const ML: f64 = 70.0;
const MT: f64 = 64.0;
const MR: f64 = 30.0;
const MB: f64 = 50.0;
/// The narrowest picture: room for the title and the legend.
const MIN_W: f64 = 560.0;

/// The raw stock, as the drawing shows it: a cylinder on the spindle axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stock {
    /// Diameter, mm.
    pub diameter: f64,
    /// Z of its right face, mm.
    pub right: f64,
    /// Z of its left end, mm (`right > left`).
    pub left: f64,
}

impl Stock {
    /// A bar of `diameter` and `length` whose face is at Z0, as the
    /// `[BILLET X… Z…` line of a simulator and `--stock` give it.
    pub fn bar(diameter: f64, length: f64) -> Stock {
        Stock {
            diameter,
            right: 0.0,
            left: -length,
        }
    }
}

/// A point marked on the drawing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Mark {
    /// Where the tool stands when the program starts.
    Start,
    /// A tool change, with the new tool's number.
    Tool(u32),
}

/// The frame of the drawing in mm: Z and radius ranges.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// The smallest Z shown, mm.
    pub zmin: f64,
    /// The largest Z shown, mm.
    pub zmax: f64,
    /// The smallest radius shown, mm.
    pub rmin: f64,
    /// The largest radius shown, mm.
    pub rmax: f64,
}

impl Frame {
    fn empty() -> Frame {
        Frame {
            zmin: f64::INFINITY,
            zmax: f64::NEG_INFINITY,
            rmin: f64::INFINITY,
            rmax: f64::NEG_INFINITY,
        }
    }

    fn grow(&mut self, (z, r): (f64, f64)) {
        self.zmin = self.zmin.min(z);
        self.zmax = self.zmax.max(z);
        self.rmin = self.rmin.min(r);
        self.rmax = self.rmax.max(r);
    }

    fn is_empty(&self) -> bool {
        !self.zmin.is_finite()
    }
}

#[derive(Debug, Clone, Default)]
/// The XZ toolpath, collected period by period and drawn as SVG.
pub struct Plot {
    runs: Vec<(Motion, Vec<(f64, f64)>)>,
    /// The last set point, kept even when dropped, to end each run on it.
    last: Option<(Motion, (f64, f64))>,
    /// Machine minus work of the last set point, (Z, radius): where it
    /// changes the work frame moved (`reframe`).
    shift: Option<(f64, f64)>,
    marks: Vec<(Mark, (f64, f64))>,
    tool: Option<u32>,
    stock: Option<Stock>,
}

impl Plot {
    /// An empty plot.
    pub fn new() -> Plot {
        Plot::default()
    }

    /// Draws the stock (and frames the drawing on it as well).
    pub fn set_stock(&mut self, stock: Stock) {
        self.stock = Some(stock);
    }

    /// Accounts one period (work coordinates: what the program wrote).
    pub fn add(&mut self, p: &SetPoint) {
        let pt = (p.z, p.x * 0.5);
        self.reframe(pt, (p.axis_z - p.z, 0.5 * (p.axis_x - p.x)));
        if self.last.is_none() {
            self.marks.push((Mark::Start, pt));
        }
        if self.tool != Some(p.tool) {
            if p.tool != 0 {
                self.marks.push((Mark::Tool(p.tool), pt));
            }
            self.tool = Some(p.tool);
        }
        // The plot draws a curve as a feed and a dwell as standing.
        let kind = match p.motion {
            Motion::Arc => Motion::Feed,
            Motion::Dwell => Motion::None,
            k => k,
        };
        if kind == Motion::None {
            self.close();
            self.last = Some((kind, pt));
            return;
        }
        let open = matches!(self.runs.last(), Some((k, _)) if *k == kind)
            && matches!(self.last, Some((k, _)) if k != Motion::None);
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

    /// Ends the open run on the last point seen. A run is open while the
    /// last point moved: a standing one (or a frame change) closed it
    /// already, and its point may lie in another frame than the run.
    fn close(&mut self) {
        let Some((kind, q)) = self.last else { return };
        if kind == Motion::None {
            return;
        }
        if let Some((_, pts)) = self.runs.last_mut() {
            if pts.last() != Some(&q) {
                pts.push(q);
            }
        }
    }

    /// An origin change (G50, G52, G54–G59, a tool offset a G28 cancels)
    /// moves the work point without motion: the open run ends, and the
    /// next one starts where the axes stood, in the new frame, so no
    /// segment joins the two frames. A tool offset taking effect changes
    /// the shift while the work point stands: nothing to do.
    fn reframe(&mut self, pt: (f64, f64), shift: (f64, f64)) {
        let Some(old) = self.shift.replace(shift) else {
            return;
        };
        let Some((_, q)) = self.last else { return };
        if !differ(old, shift) || !differ(q, pt) {
            return;
        }
        self.close();
        let at = (q.0 + old.0 - shift.0, q.1 + old.1 - shift.1);
        self.last = Some((Motion::None, at));
    }

    /// The leftmost Z of the cutting moves, if anything was cut.
    pub fn cut_zmin(&self) -> Option<f64> {
        self.runs
            .iter()
            .filter(|(k, _)| matches!(k, Motion::Feed | Motion::Thread))
            .flat_map(|(_, pts)| pts.iter().map(|p| p.0))
            .reduce(f64::min)
    }

    /// The marks so far: the start point and each tool change, (Z, radius).
    pub fn marks(&self) -> &[(Mark, (f64, f64))] {
        &self.marks
    }

    /// The frame in mm: the cutting moves, the stock and the spindle axis,
    /// with a margin of a twentieth of the larger side; all moves when
    /// nothing cuts.
    pub fn frame(&self) -> Frame {
        let mut f = Frame::empty();
        for (kind, pts) in &self.runs {
            if matches!(kind, Motion::Feed | Motion::Thread) {
                pts.iter().for_each(|&p| f.grow(p));
            }
        }
        if let Some(s) = self.stock {
            f.grow((s.left, 0.0));
            f.grow((s.right, 0.5 * s.diameter));
        }
        if f.is_empty() {
            for (_, pts) in &self.runs {
                pts.iter().for_each(|&p| f.grow(p));
            }
            self.marks.iter().for_each(|&(_, p)| f.grow(p));
        }
        if f.is_empty() {
            f = Frame {
                zmin: -1.0,
                zmax: 1.0,
                rmin: -1.0,
                rmax: 1.0,
            };
        }
        f.rmin = f.rmin.min(0.0);
        f.rmax = f.rmax.max(0.0);
        let pad = 0.05 * (f.zmax - f.zmin).max(f.rmax - f.rmin).max(1.0);
        Frame {
            zmin: f.zmin - pad,
            zmax: f.zmax + pad,
            rmin: f.rmin - pad,
            rmax: f.rmax + pad,
        }
    }

    /// The SVG document; `title` names the program.
    pub fn svg(&mut self, title: &str) -> String {
        self.close();
        let v = View::new(self.frame());
        let mut s = String::new();
        v.header(&mut s, title);
        if let Some(st) = self.stock {
            let (x0, y0) = v.px((st.left, 0.5 * st.diameter));
            let (x1, y1) = v.px((st.right, 0.0));
            let _ = writeln!(
                s,
                "<rect x=\"{x0:.1}\" y=\"{y0:.1}\" width=\"{:.1}\" height=\"{:.1}\" fill=\"#f1e6c8\" stroke=\"#b59a55\" clip-path=\"url(#frame)\"/>",
                x1 - x0,
                y1 - y0
            );
        }
        v.axis(&mut s);
        let tol_mm = TOLERANCE_PX / v.scale;
        let mut arrows = Vec::new();
        s.push_str("<g fill=\"none\" clip-path=\"url(#frame)\">\n");
        for (kind, pts) in &self.runs {
            if pts.len() < 2 {
                continue;
            }
            let pts = simplify(pts, tol_mm);
            let style = match kind {
                Motion::Rapid => "stroke=\"#d62728\" stroke-width=\"1\" stroke-dasharray=\"6 4\"",
                Motion::Thread => "stroke=\"#2ca02c\" stroke-width=\"1.6\"",
                _ => "stroke=\"#1f4e9c\" stroke-width=\"1.4\"",
            };
            s.push_str("<polyline ");
            s.push_str(style);
            s.push_str(" points=\"");
            for w in pts.windows(2) {
                arrows.extend(v.crossing(v.px(w[0]), v.px(w[1])));
            }
            for &p in &pts {
                let (x, y) = v.px(p);
                let _ = write!(s, "{x:.1},{y:.1} ");
            }
            s.push_str("\"/>\n");
        }
        s.push_str("</g>\n");
        for (at, dir) in arrows {
            arrow(&mut s, at, dir);
        }
        self.draw_marks(&mut s, &v);
        s.push_str("</svg>\n");
        s
    }

    /// The start point (a ring) and the tool changes (a triangle and the
    /// tool number); a mark outside the frame sits on its edge, and labels
    /// that would fall on one another are stacked.
    fn draw_marks(&self, s: &mut String, v: &View) {
        let mut placed: Vec<(f64, f64)> = Vec::new();
        for &(mark, p) in &self.marks {
            let (x, y) = v.pin(v.px(p));
            // Above the mark, or below it on the frame's top edge, where
            // the label would reach into the legend.
            let mut ly = if y <= v.y0 { y + 14.0 } else { y - 6.0 };
            while placed
                .iter()
                .any(|&(px, py)| (px - x).abs() < 40.0 && (py - ly).abs() < 12.0)
            {
                ly += 13.0;
            }
            placed.push((x, ly));
            let text = match mark {
                Mark::Start => String::from("start"),
                Mark::Tool(t) => {
                    let mut t2 = String::new();
                    let _ = write!(t2, "T{t:02}");
                    t2
                }
            };
            match mark {
                Mark::Start => {
                    let _ = writeln!(
                        s,
                        "<circle cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"4\" fill=\"none\" stroke=\"#000\" stroke-width=\"1.5\"/>"
                    );
                }
                Mark::Tool(_) => {
                    let _ = writeln!(
                        s,
                        "<path d=\"M{x:.1} {y:.1} l-4 -7 h8 z\" fill=\"#7b3294\"/>"
                    );
                }
            }
            let _ = writeln!(
                s,
                "<text x=\"{:.1}\" y=\"{ly:.1}\" fill=\"#333\" font-size=\"11\">{text}</text>",
                x + 6.0
            );
        }
    }
}

/// Two points (or shifts) further apart than rounding: machine − work
/// is computed afresh each period, and a tool offset's last period puts
/// the work point back within rounding of where it stood.
fn differ(a: (f64, f64), b: (f64, f64)) -> bool {
    (a.0 - b.0).abs() > 1e-9 || (a.1 - b.1).abs() > 1e-9
}

/// The mapping from mm to pixels and the fixed parts of the picture.
struct View {
    f: Frame,
    scale: f64,
    /// The drawing area, pixels.
    x0: f64,
    y0: f64,
    x1: f64,
    y1: f64,
    w: f64,
    h: f64,
}

impl View {
    fn new(f: Frame) -> View {
        let mut scale = MAX_W / (f.zmax - f.zmin);
        if (f.rmax - f.rmin) * scale > MAX_H {
            scale = MAX_H / (f.rmax - f.rmin);
        }
        let (pw, ph) = ((f.zmax - f.zmin) * scale, (f.rmax - f.rmin) * scale);
        let w = (pw + ML + MR).max(MIN_W);
        View {
            f,
            scale,
            x0: ML,
            y0: MT,
            x1: ML + pw,
            y1: MT + ph,
            w,
            h: ph + MT + MB,
        }
    }

    fn px(&self, (z, r): (f64, f64)) -> (f64, f64) {
        (
            self.x0 + (z - self.f.zmin) * self.scale,
            self.y0 + (self.f.rmax - r) * self.scale,
        )
    }

    fn inside(&self, (x, y): (f64, f64)) -> bool {
        (self.x0..=self.x1).contains(&x) && (self.y0..=self.y1).contains(&y)
    }

    /// A point moved onto the frame's edge if it is outside.
    fn pin(&self, (x, y): (f64, f64)) -> (f64, f64) {
        (x.clamp(self.x0, self.x1), y.clamp(self.y0, self.y1))
    }

    /// Where the segment `a`→`b` crosses the frame's edge, if exactly one
    /// end is inside, and its unit direction.
    fn crossing(&self, a: (f64, f64), b: (f64, f64)) -> Option<((f64, f64), (f64, f64))> {
        let (ia, ib) = (self.inside(a), self.inside(b));
        if ia == ib {
            return None;
        }
        let (d, len) = {
            let (dx, dy) = (b.0 - a.0, b.1 - a.1);
            let len = libm::hypot(dx, dy);
            ((dx / len, dy / len), len)
        };
        // The inside end, walked towards the outside one: the first edge
        // reached is the crossing.
        let (from, dir) = if ia { (a, d) } else { (b, (-d.0, -d.1)) };
        let mut t = len;
        for (edge, p, v) in [
            (self.x0, from.0, dir.0),
            (self.x1, from.0, dir.0),
            (self.y0, from.1, dir.1),
            (self.y1, from.1, dir.1),
        ] {
            if v != 0.0 {
                let te = (edge - p) / v;
                if te >= 0.0 && te < t {
                    t = te;
                }
            }
        }
        let at = (from.0 + t * dir.0, from.1 + t * dir.1);
        Some((at, d))
    }

    /// The white page, the title and legend, the grid and tick labels, the
    /// frame and its clip path.
    fn header(&self, s: &mut String, title: &str) {
        let (w, h) = (self.w, self.h);
        let _ = writeln!(
            s,
            "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"{w:.0}\" height=\"{h:.0}\" viewBox=\"0 0 {w:.1} {h:.1}\" font-family=\"sans-serif\" font-size=\"12\">"
        );
        let _ = writeln!(s, "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>");
        let _ = writeln!(
            s,
            "<defs><clipPath id=\"frame\"><rect x=\"{:.1}\" y=\"{:.1}\" width=\"{:.1}\" height=\"{:.1}\"/></clipPath></defs>",
            self.x0,
            self.y0,
            self.x1 - self.x0,
            self.y1 - self.y0
        );
        // The title on the first line, the legend on its own line below:
        // however long the title, they cannot overlap.
        let _ = writeln!(
            s,
            "<text x=\"{ML}\" y=\"22\" font-size=\"15\" font-weight=\"bold\">{}</text>",
            escape(title)
        );
        legend(s, ML, 44.0);
        self.grid(s);
        let _ = writeln!(
            s,
            "<rect x=\"{:.1}\" y=\"{:.1}\" width=\"{:.1}\" height=\"{:.1}\" fill=\"none\" stroke=\"#888\"/>",
            self.x0,
            self.y0,
            self.x1 - self.x0,
            self.y1 - self.y0
        );
        let _ = writeln!(
            s,
            "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\">Z (mm)</text>",
            (self.x0 + self.x1) / 2.0,
            h - 12.0
        );
        let mid = (self.y0 + self.y1) / 2.0;
        let _ = writeln!(
            s,
            "<text x=\"16\" y=\"{mid:.1}\" transform=\"rotate(-90 16 {mid:.1})\" text-anchor=\"middle\">X (diameter, mm)</text>"
        );
    }

    fn grid(&self, s: &mut String) {
        let f = self.f;
        let step_z = nice_step((f.zmax - f.zmin) / 8.0);
        let step_r = nice_step((f.rmax - f.rmin) / 6.0);
        let mut z = libm::ceil(f.zmin / step_z) * step_z;
        while z <= f.zmax {
            let (x, _) = self.px((z, 0.0));
            let _ = writeln!(
                s,
                "<line x1=\"{x:.1}\" y1=\"{:.1}\" x2=\"{x:.1}\" y2=\"{:.1}\" stroke=\"#e4e4e4\"/><text x=\"{x:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{}</text>",
                self.y0,
                self.y1,
                self.y1 + 16.0,
                label(z)
            );
            z += step_z;
        }
        let mut r = libm::ceil(f.rmin / step_r) * step_r;
        while r <= f.rmax {
            let (_, y) = self.px((0.0, r));
            let _ = writeln!(
                s,
                "<line x1=\"{:.1}\" y1=\"{y:.1}\" x2=\"{:.1}\" y2=\"{y:.1}\" stroke=\"#e4e4e4\"/><text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"end\">{}</text>",
                self.x0,
                self.x1,
                self.x0 - 6.0,
                y + 4.0,
                label(2.0 * r)
            );
            r += step_r;
        }
    }

    /// The spindle axis, a chain line.
    fn axis(&self, s: &mut String) {
        let (_, y) = self.px((0.0, 0.0));
        let _ = writeln!(
            s,
            "<line x1=\"{:.1}\" y1=\"{y:.1}\" x2=\"{:.1}\" y2=\"{y:.1}\" stroke=\"#999\" stroke-dasharray=\"12 3 2 3\"/>",
            self.x0, self.x1
        );
    }
}

/// The key to the line styles, left to right from `(x, y)`.
fn legend(s: &mut String, x: f64, y: f64) {
    let items = [
        ("rapid", "#d62728", "6 4"),
        ("feed", "#1f4e9c", ""),
        ("thread", "#2ca02c", ""),
        ("stock", "#b59a55", ""),
    ];
    for (i, (name, colour, dash)) in items.iter().enumerate() {
        let lx = x + 80.0 * i as f64;
        let _ = writeln!(
            s,
            "<line x1=\"{lx:.1}\" y1=\"{:.1}\" x2=\"{:.1}\" y2=\"{:.1}\" stroke=\"{colour}\" stroke-width=\"1.6\" stroke-dasharray=\"{dash}\"/><text x=\"{:.1}\" y=\"{y:.1}\">{name}</text>",
            y - 4.0,
            lx + 26.0,
            y - 4.0,
            lx + 32.0,
        );
    }
    let lx = x + 80.0 * items.len() as f64;
    let _ = writeln!(
        s,
        "<circle cx=\"{:.1}\" cy=\"{:.1}\" r=\"4\" fill=\"none\" stroke=\"#000\" stroke-width=\"1.5\"/><text x=\"{:.1}\" y=\"{y:.1}\">start</text>",
        lx + 5.0,
        y - 4.0,
        lx + 14.0
    );
    let lx = lx + 64.0;
    let _ = writeln!(
        s,
        "<path d=\"M{:.1} {:.1} l-4 -7 h8 z\" fill=\"#7b3294\"/><text x=\"{:.1}\" y=\"{y:.1}\">tool change</text>",
        lx + 5.0,
        y,
        lx + 14.0
    );
}

/// A filled arrow head whose tip is at `at`, pointing along `d`.
fn arrow(s: &mut String, at: (f64, f64), d: (f64, f64)) {
    let n = (-d.1, d.0);
    let base = (at.0 - 9.0 * d.0, at.1 - 9.0 * d.1);
    let _ = writeln!(
        s,
        "<path class=\"leaves\" d=\"M{:.1} {:.1} L{:.1} {:.1} L{:.1} {:.1} z\" fill=\"#d62728\"/>",
        at.0,
        at.1,
        base.0 + 4.0 * n.0,
        base.1 + 4.0 * n.1,
        base.0 - 4.0 * n.0,
        base.1 - 4.0 * n.1
    );
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

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::vec;

    /// A period at work X`x` Z`z`, the axes there too (no work offset).
    fn at(x: f64, z: f64, motion: Motion, tool: u32) -> SetPoint {
        SetPoint {
            x,
            z,
            axis_x: x,
            axis_z: z,
            motion,
            tool,
            ..SetPoint::default()
        }
    }

    /// A period at work X`x` Z`z` (X a diameter) whose axes stand at
    /// work + `shift` (X diameter, Z).
    fn shifted(x: f64, z: f64, shift: (f64, f64), motion: Motion) -> SetPoint {
        SetPoint {
            axis_x: x + shift.0,
            axis_z: z + shift.1,
            ..at(x, z, motion, 1)
        }
    }

    /// The runs of a plot of one kind, (Z, radius) points.
    fn runs_of(p: &Plot, kind: Motion) -> Vec<Vec<(f64, f64)>> {
        let runs = p.runs.iter().filter(|(k, _)| *k == kind);
        runs.map(|(_, pts)| pts.clone()).collect()
    }

    /// `G00 X20 Z5; G01 Z-10; G50 X60 Z20; G01 Z0; G00 X80 Z30` from
    /// machine zero, no work offset: G50 makes machine X20 Z−10 work X60
    /// Z20, a shift (machine − work) of X−40 Z−30. The cuts are Z5 → Z−10
    /// at radius 10 and Z20 → Z0 at radius 30, two runs; the last rapid
    /// starts at the second cut's end, (Z0, r30).
    #[test]
    fn an_origin_change_draws_no_segment() {
        let (old, new) = ((0.0, 0.0), (-40.0, -30.0));
        let mut p = Plot::new();
        p.add(&shifted(0.0, 0.0, old, Motion::None));
        p.add(&shifted(10.0, 2.5, old, Motion::Rapid));
        p.add(&shifted(20.0, 5.0, old, Motion::Rapid));
        p.add(&shifted(20.0, 5.0, old, Motion::None));
        p.add(&shifted(20.0, -2.0, old, Motion::Feed));
        p.add(&shifted(20.0, -10.0, old, Motion::Feed));
        p.add(&shifted(20.0, -10.0, old, Motion::None));
        // The first period after G50 moves from rest: 0.001 mm.
        p.add(&shifted(60.0, 19.999, new, Motion::Feed));
        p.add(&shifted(60.0, 0.0, new, Motion::Feed));
        p.add(&shifted(60.0, 0.0, new, Motion::None));
        p.add(&shifted(80.0, 30.0, new, Motion::Rapid));
        p.close();
        let feeds = runs_of(&p, Motion::Feed);
        assert_eq!(
            feeds,
            [
                vec![(5.0, 10.0), (-2.0, 10.0), (-10.0, 10.0)],
                // (19.999 is within KEEP_MM of the start: dropped.)
                vec![(20.0, 30.0), (0.0, 30.0)]
            ]
        );
        let rapids = runs_of(&p, Motion::Rapid);
        assert_eq!(
            rapids,
            [
                vec![(0.0, 0.0), (2.5, 5.0), (5.0, 10.0)],
                vec![(0.0, 30.0), (30.0, 40.0)]
            ]
        );
    }

    /// G52 between two rapids, the frame changing while the axes stand (a
    /// standing period in the new frame): the first rapid ends where it
    /// went, the second starts where the axes stood, in the new frame.
    /// G52 X5 Z5 at work X10 Z0 makes it X5 Z−5 (shift X+5 Z+5).
    #[test]
    fn a_standing_origin_change_leaves_the_run_before_alone() {
        let (old, new) = ((0.0, 0.0), (5.0, 5.0));
        let mut p = Plot::new();
        p.add(&shifted(0.0, 10.0, old, Motion::None));
        p.add(&shifted(10.0, 0.0, old, Motion::Rapid));
        p.add(&shifted(10.0, 0.0, old, Motion::None));
        p.add(&shifted(5.0, -5.0, new, Motion::None));
        p.add(&shifted(5.0, -5.0, new, Motion::Dwell));
        p.add(&shifted(0.0, 0.0, new, Motion::Rapid));
        p.close();
        let rapids = runs_of(&p, Motion::Rapid);
        assert_eq!(
            rapids,
            [vec![(10.0, 0.0), (0.0, 5.0)], vec![(-5.0, 2.5), (0.0, 0.0)]]
        );
    }

    /// A tool offset taking effect moves the axes while the work point
    /// stands: no frame change for the plot, and the rapid after it
    /// starts from the work point.
    #[test]
    fn a_tool_offset_is_no_frame_change() {
        let mut p = Plot::new();
        p.add(&shifted(100.0, 50.0, (-100.0, -50.0), Motion::None));
        p.add(&shifted(100.0, 50.0, (-101.0, -49.5), Motion::Rapid));
        p.add(&shifted(100.0, 50.0, (-102.5, -48.8), Motion::Rapid));
        p.add(&shifted(100.0, 50.0, (-102.5, -48.8), Motion::None));
        p.add(&shifted(20.0, 5.0, (-102.5, -48.8), Motion::Rapid));
        p.close();
        let rapids = runs_of(&p, Motion::Rapid);
        assert_eq!(
            rapids,
            [vec![(50.0, 50.0)], vec![(50.0, 50.0), (5.0, 10.0)]]
        );
    }

    /// A part cut between Z0 and Z−50 at diameters 20 to 40, with a
    /// rapid out to the tool-change point X200 Z200 and back.
    fn part() -> Plot {
        let mut p = Plot::new();
        p.add(&at(200.0, 200.0, Motion::None, 1));
        p.add(&at(40.0, 0.0, Motion::Rapid, 1));
        for i in 1..=500 {
            p.add(&at(40.0, -0.1 * i as f64, Motion::Feed, 1));
        }
        p.add(&at(20.0, -50.0, Motion::Feed, 1));
        p.add(&at(200.0, 200.0, Motion::Rapid, 1));
        p.add(&at(200.0, 200.0, Motion::None, 2));
        p
    }

    #[test]
    fn the_frame_is_the_cut_not_the_rapids() {
        // Cut: Z −50…0, radius 10…20, and the axis (radius 0): 50 × 20 mm;
        // the margin is 5 % of the larger side, 2.5 mm.
        let f = part().frame();
        assert_eq!(
            f,
            Frame {
                zmin: -52.5,
                zmax: 2.5,
                rmin: -2.5,
                rmax: 22.5
            }
        );
    }

    #[test]
    fn the_stock_widens_the_frame() {
        // A bar of Ø50 × 60 with its face at Z0: Z −60…0, radius 0…25,
        // margin 3 mm.
        let mut p = part();
        p.set_stock(Stock::bar(50.0, 60.0));
        assert_eq!(
            p.frame(),
            Frame {
                zmin: -63.0,
                zmax: 3.0,
                rmin: -3.0,
                rmax: 28.0
            }
        );
        assert!(p.svg("O0001").contains("fill=\"#f1e6c8\""));
    }

    #[test]
    fn rapids_that_leave_the_frame_get_an_arrow() {
        // One rapid comes in from the tool-change point and one goes back:
        // two crossings of the frame's edge.
        let svg = part().svg("t");
        assert_eq!(svg.matches("class=\"leaves\"").count(), 2, "{svg}");
    }

    #[test]
    fn start_and_tool_changes_are_marked() {
        let p = part();
        let marks: Vec<Mark> = p.marks().iter().map(|m| m.0).collect();
        assert_eq!(marks, [Mark::Start, Mark::Tool(1), Mark::Tool(2)]);
        let svg = part().svg("t");
        assert!(svg.contains(">T01</text>") && svg.contains(">T02</text>"));
    }

    #[test]
    fn the_straight_feed_is_two_points() {
        // 500 periods along X40 from Z0 to Z−50, then a step down to X20:
        // the feed run draws as its three corners, (0, 20), (−50, 20) and
        // (−50, 10).
        let svg = part().svg("t");
        let feed = svg
            .lines()
            .find(|l| l.contains("#1f4e9c\" stroke-width=\"1.4\""))
            .unwrap_or_default();
        let n = feed
            .split_once("points=\"")
            .and_then(|(_, p)| p.split_once('"'))
            .map_or(0, |(p, _)| p.split_whitespace().count());
        assert_eq!(n, 3, "{feed}");
    }

    #[test]
    fn the_legend_sits_below_the_title() {
        let svg = part().svg("a very long program name O0201 (P02-105-008-2326-D6 OP2)");
        let title_y = svg.find("font-weight=\"bold\"").map(|_| 22.0);
        assert_eq!(title_y, Some(22.0));
        // Legend text baselines are at y=44, 22 px under the title's, and
        // the drawing (its clip rectangle) starts 20 px below that.
        assert!(svg.contains("y=\"44.0\">rapid</text>"));
        assert!(svg.contains("<clipPath id=\"frame\"><rect x=\"70.0\" y=\"64.0\""));
    }
}
