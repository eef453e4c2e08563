//! Point-set input and output.
