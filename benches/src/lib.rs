//! Criterion benches of gbc.
