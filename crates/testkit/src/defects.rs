//! Meshes with the defects of real CAD exports (filled in by the repair work).
