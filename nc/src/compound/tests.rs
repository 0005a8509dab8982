//! Hand-checked paths of G70–G73 through `Nc::exec`.
