//! Stage 2: expressions. (Being built.)
