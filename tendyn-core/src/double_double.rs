//! placeholder while the double-double scalar is written
