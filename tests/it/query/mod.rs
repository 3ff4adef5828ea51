//! Point and ray queries: the methods agree, batches match single queries,
//! exact signs over the whole `f64` range, the hard cases, high-valence
//! vertices, and the winding number of soups.

mod agreement;
mod batch;
mod full_range;
mod hard_cases;
mod high_valence;
mod soup_winding;
