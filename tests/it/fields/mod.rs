//! Fields and cells: marching cubes, marching by blocks, octree cells with
//! certified volumes.

mod cells;
mod marching_blocks;
mod marching_cubes;
