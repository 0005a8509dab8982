//! The canon's side: the events, in program order, queue the end points
//! the path must reach and set the spindle and the frame they are
//! checked in.

use super::pending::{Pending, Shape};
use super::shape::comes_back;
use super::{axis_steps, chain_corner_mm, Certifier, END_POINT_MM};
use crate::math::V2;
use crate::polar::PlaneMap;
use nc::event::SpindleDir;
use nc::{Event, Sink};

impl Sink for Certifier {
    fn emit(&mut self, e: Event) {
        // Consecutive thread moves form a chain; anything between ends it.
        let thread = matches!(e, Event::Thread { .. });
        match e {
            Event::Line { x, z, .. } | Event::Skip { x, z } => {
                self.push_move(x, z, None, Shape::Line)
            }
            Event::Arc { dir, x, z, cx, cz } => {
                let centre = V2::from_xz(cx, cz);
                let ccw = dir == nc::event::Dir::Ccw;
                self.push_move(x, z, None, Shape::Arc { centre, ccw })
            }
            Event::Rapid { x, z, .. } => self.push_move(x, z, None, Shape::Rapid),
            Event::Ellipse { x, z, .. }
            | Event::Parabola { x, z, .. }
            | Event::ArcThread { x, z, .. } => self.push_move(x, z, None, Shape::Free),
            Event::Thread {
                x, z, lead, dlead, ..
            } => self.push_move(x, z, Some((lead, dlead.unwrap_or(0.0))), Shape::Thread),
            Event::Speed { s, css, max } => {
                if let Some(m) = max {
                    self.cmd.clamp = if m > 0.0 { m } else { f64::INFINITY };
                }
                self.cmd.css = css.then_some(s.max(0.0));
            }
            Event::Spindle(d) => self.cmd.on = d != SpindleDir::Stop,
            // The tool goes home by a way of its own: the next move's
            // start is not the last end point.
            Event::Home { .. } => self.last_end = None,
            // The plane's moves: where they leave the joints (the runtime's
            // translator, translate.rs), so that the move after the plane
            // starts there.
            Event::PolarOn => self.plane_on(PlaneMap::Polar { z: 0.0 }),
            Event::Cylinder(Some(radius)) => self.plane_on(PlaneMap::Cylinder { radius, r: 0.0 }),
            Event::PlaneMove { a, b, off, .. } => self.plane_move(a, b, off),
            Event::PlaneAxis { to, c, .. } => self.plane_axis(to, c),
            Event::PolarOff { x, .. } => self.plane_off(Some(x)),
            Event::Cylinder(None) => self.plane_off(None),
            // A new work zero (machine coordinates, X a diameter): the last
            // end point, where the next move starts, is the same place in
            // the new frame (unknown when the old zero was never printed).
            Event::Origin { x, z } => {
                let origin = V2::from_xz(x, z);
                let shift = self.origin.map(|old| origin - old);
                self.last_end = self.last_end.zip(shift).map(|(e, s)| e - s);
                if let Some(t) = &mut self.plane {
                    t.r = t.r.zip(shift).map(|(r, s)| r - s.r);
                    t.z = t.z.zip(shift).map(|(z, s)| z - s.z);
                }
                self.origin = Some(origin);
            }
            _ => {}
        }
        self.chain_open = thread;
    }
}

impl Certifier {
    /// A canon move to `x` (a diameter), `z`, work coordinates: its end
    /// point joins the queue (`thread`: lead and lead change; a thread
    /// move after another continues the chain at speed).
    fn push_move(&mut self, x: f64, z: f64, thread: Option<(f64, f64)>, shape: Shape) {
        let end = V2::from_xz(x, z);
        self.end_points += 1;
        let mut enter = V2::ZERO;
        // A thread move that continues a chain: the corner where the
        // previous one ends is taken at thread speed.
        if let (true, Some(out), Some(start)) = (self.chain_open, thread, self.last_end) {
            let ax = self.axes[0].map_or(0.0, |a| a.accel);
            let az = self.axes[1].map_or(0.0, |a| a.accel);
            let dt = self.dt;
            if let Some(prev) = self.pending.back_mut() {
                if let (Some(inc), Some(from)) = (prev.thread, prev.start) {
                    let legs = [(prev.end - from, inc), (end - start, out)];
                    prev.tol = END_POINT_MM.max(chain_corner_mm(legs, [ax, az], dt));
                    prev.corner = true;
                    enter = axis_steps(legs);
                }
            }
            self.widen_before_corner();
        }
        self.pending.push_back(Pending {
            end,
            start: self.last_end,
            thread,
            tol: END_POINT_MM,
            enter,
            corner: false,
            shape,
            spindle: self.cmd,
            nearest: f64::INFINITY,
            at: (0.0, 0, 0),
            plane: None,
            away: comes_back(self.last_end, end, shape),
        });
        self.last_end = Some(end);
    }
}
