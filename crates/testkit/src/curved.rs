//! Tessellated curved parts whose fits interpenetrate by a known depth.
