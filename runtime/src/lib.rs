//! The real-time interpolation runtime of gbc: not built yet (issue 6).
