//! Point classification in large batches, in grid-cell order: consecutive
//! queries then meet the same triangles, which stay in cache, instead of
//! fetching a random part of the mesh from memory for every point.

use glam::DVec3;
use rayon::prelude::*;

use super::Accel;
use super::Containment;
use super::x_direction::RayChoice;
use super::x_ray::XRay;

/// Points per rayon task (and per gathered buffer, 96 KiB).
const POINTS_PER_TASK: usize = 4096;

impl Accel {
    /// [`Accel::x_ray_towards`] of every point with `choice`, turned into an
    /// answer by `finish(point, ray)`; the answers in input order.
    pub(super) fn x_ray_batch(
        &self,
        points: &[DVec3],
        choice: RayChoice,
        finish: impl Fn(DVec3, XRay) -> Containment + Sync,
    ) -> Vec<Containment> {
        let g = self.grid();
        // A counting sort by cell, O(n + cells): `order` lists the point
        // indices cell by cell. Only indices move here: the random writes
        // are 4 bytes each.
        let cells: Vec<u32> = points
            .par_iter()
            .with_min_len(4096)
            .map(|p| g.cell_index(p.y, p.z) as u32)
            .collect();
        let mut start = vec![0u32; g.cell_count() + 1];
        for &c in &cells {
            start[c as usize + 1] += 1;
        }
        for i in 0..g.cell_count() {
            start[i + 1] += start[i];
        }
        // The scatter, in parallel: each task owns a run of cells and so a
        // disjoint part of `order`, and picks its points out of `cells`.
        let mut order = vec![0u32; points.len()];
        let tasks = rayon::current_num_threads().clamp(1, 16);
        let mut runs: Vec<(usize, usize, &mut [u32])> = Vec::with_capacity(tasks);
        let mut rest: &mut [u32] = &mut order;
        let mut first = 0;
        for k in 1..=tasks {
            let last = if k == tasks {
                g.cell_count()
            } else {
                start
                    .partition_point(|&s| (s as usize) < points.len() * k / tasks)
                    .saturating_sub(1)
            }
            .max(first);
            let taken = (start[last] - start[first]) as usize;
            let (head, tail) = std::mem::take(&mut rest).split_at_mut(taken);
            runs.push((first, last, head));
            rest = tail;
            first = last;
        }
        runs.into_par_iter().for_each(|(c0, c1, out)| {
            let base = start[c0];
            let mut fill: Vec<u32> = start[c0..c1].iter().map(|&s| s - base).collect();
            for (i, &c) in cells.iter().enumerate() {
                let c = c as usize;
                if (c0..c1).contains(&c) {
                    let slot = &mut fill[c - c0];
                    out[*slot as usize] = i as u32;
                    *slot += 1;
                }
            }
        });
        drop(start);
        drop(cells);
        // The answers in that order, a run of points at a time: each run is
        // first gathered into a small buffer (a loop without branches keeps
        // many cache misses in flight at once), then classified.
        let mut sorted = vec![Containment::Outside; points.len()];
        sorted
            .par_chunks_mut(POINTS_PER_TASK)
            .zip(order.par_chunks(POINTS_PER_TASK))
            .for_each(|(out, run)| {
                let group: Vec<DVec3> = run.iter().map(|&i| points[i as usize]).collect();
                for (answer, &p) in out.iter_mut().zip(&group) {
                    *answer = finish(p, self.x_ray_towards(p, choice));
                }
            });
        let mut answers = vec![Containment::Outside; points.len()];
        for (&i, &a) in order.iter().zip(&sorted) {
            answers[i as usize] = a;
        }
        answers
    }
}
