//! Placeholder: bounding-volume hierarchy lands here.
