//! Layer 1, the basic types: points and units, the G-code table, words,
//! the machine configuration, events, the geometry element and the typed
//! errors. Nothing here refers to the state of a running kernel.

pub mod alarm;
pub mod canon_line;
pub mod decimal;
pub mod error;
pub mod event;
pub mod gcode;
pub mod geom;
pub mod machine;
pub mod machine_check;
pub mod mcode;
pub mod nesting;
pub mod offset_page;
pub mod plc;
pub mod point;
pub mod thread_room;
pub mod words;
