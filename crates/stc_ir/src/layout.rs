//! Memory layout of types (filled in next).
