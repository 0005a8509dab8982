//! Layer 4, the planners: geometry as pure functions of typed arguments
//! (elements, points, the machine's settings) that return typed path
//! elements and never touch the executing kernel. The executor (layer 5)
//! calls them.

pub mod angle;
pub mod comp;
pub mod conic;
pub mod corner;
pub mod curve;
pub mod drill;
pub mod elem;
pub mod groove;
pub mod legs;
pub mod offset;
pub mod profile;
pub mod reader;
pub mod roughing;
pub mod single;
pub mod thread;
pub mod threading;
