//! Marching by blocks (`try_mesh`) skips the blocks a field's bound shows
//! to be all inside or all outside, and gives the very soup the whole grid
//! gives (`SampleGrid::try_sample` then `march_grid`), bit for bit.

use glam::DVec3;
use proptest::prelude::*;
use wingedge::SetOp;
use wingedge::field::marching::march_grid;
use wingedge::field::{
    Blobs, Falloff, Field, FieldCsg, MarchingOptions, Meshed, Placement, SampleGrid, Source,
    try_mesh,
};

fn blobs(sources: &[(DVec3, f64, f64)], falloff: Falloff) -> Blobs {
    Blobs::try_new(
        sources
            .iter()
            .map(|&(c, r, w)| Source::try_new(c, r, w).unwrap())
            .collect(),
        falloff,
    )
    .unwrap()
}

/// Meshes by blocks and over the whole grid; asserts the same soup, bit for
/// bit, and the same surface counts; returns the blocks' result and the
/// whole grid's sample count.
fn assert_same_as_whole_grid(field: &dyn Field, options: &MarchingOptions) -> (Meshed, u64) {
    let meshed = try_mesh(field, options).unwrap();
    let (grid, whole_stats) = SampleGrid::try_sample(field, options.resolution).unwrap();
    let (whole, march) = march_grid(&grid, options);
    assert_eq!(meshed.dims, grid.dims());
    assert_eq!(meshed.cell.to_bits(), grid.cell().to_bits());
    assert_eq!(meshed.soup.positions.len(), whole.positions.len());
    for (i, (a, b)) in meshed
        .soup
        .positions
        .iter()
        .zip(&whole.positions)
        .enumerate()
    {
        assert_eq!(
            a.to_array().map(f64::to_bits),
            b.to_array().map(f64::to_bits),
            "vertex {i}: {a} by blocks, {b} on the whole grid"
        );
    }
    assert_eq!(meshed.soup.polygons.len(), whole.polygons.len());
    for (i, (a, b)) in meshed.soup.polygons.iter().zip(&whole.polygons).enumerate() {
        assert_eq!(a.vertices, b.vertices, "triangle {i}");
    }
    assert_eq!(meshed.march.triangles, march.triangles);
    assert_eq!(meshed.march.vertices, march.vertices);
    assert_eq!(meshed.march.surface_cells, march.surface_cells);
    (meshed, whole_stats.samples)
}

#[test]
fn many_blobs_skip_most_blocks_and_mesh_as_the_whole_grid() {
    // 60 blobs scattered in a 10-unit box, a fifth of them carving.
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let sources: Vec<_> = (0..60)
        .map(|i| {
            let c = DVec3::new(10.0 * next(), 10.0 * next(), 10.0 * next());
            let w = if i % 5 == 0 { -0.7 } else { 1.0 };
            (c, 0.8 + 1.2 * next(), w)
        })
        .collect();
    let field = blobs(&sources, Falloff::SoftObject);
    for placement in [Placement::Interpolated, Placement::Midpoint] {
        let options = MarchingOptions {
            resolution: 120,
            placement,
            ..MarchingOptions::default()
        };
        let (meshed, whole_samples) = assert_same_as_whole_grid(&field, &options);
        assert!(meshed.march.triangles > 10_000, "{:?}", meshed.march);
        // Most blocks are decided by the bound, and most samples spared.
        assert!(
            meshed.march.blocks_marched * 2 < meshed.march.blocks,
            "{:?}",
            meshed.march
        );
        assert!(
            meshed.field.samples * 2 < whole_samples,
            "{} of {whole_samples}",
            meshed.field.samples
        );
    }
}

#[test]
fn a_ball_is_skipped_inside_and_outside() {
    // One source of radius 8: a ball of radius 4 at resolution 64 (cells of
    // 0.25); blocks of 8 cells are 2 units, so blocks lie wholly inside.
    let field = blobs(&[(DVec3::ZERO, 8.0, 1.0)], Falloff::CubicParabola);
    let options = MarchingOptions {
        resolution: 64,
        ..MarchingOptions::default()
    };
    let (meshed, whole_samples) = assert_same_as_whole_grid(&field, &options);
    let blocks = meshed.march.blocks;
    assert_eq!(blocks, 9 * 9 * 9);
    // The sphere of radius ~3.6 meets fewer than half of the blocks.
    assert!(
        meshed.march.blocks_marched < blocks / 2,
        "{:?}",
        meshed.march
    );
    assert!(meshed.field.samples < whole_samples / 2);
}

fn random_source() -> impl Strategy<Value = (DVec3, f64, f64)> {
    (
        (-2.0..2.0f64, -2.0..2.0f64, -2.0..2.0f64),
        0.3..2.5f64,
        prop_oneof![4 => 0.6..1.5f64, 1 => -1.0..-0.2f64],
    )
        .prop_map(|((x, y, z), r, w)| (DVec3::new(x, y, z), r, w))
}

proptest! {
    #![proptest_config(crate::common::regressions_beside_source(ProptestConfig::with_cases(120)))]

    /// Random blob fields (carving sources included) under a random field
    /// operator, either falloff, either placement: the blocks give the
    /// whole grid's soup.
    #[test]
    fn random_blob_fields_mesh_by_blocks_as_on_the_whole_grid(
        a in proptest::collection::vec(random_source(), 1..8),
        b in proptest::collection::vec(random_source(), 1..4),
        op in 0..4usize,
        resolution in 2..48usize,
        midpoints in any::<bool>(),
        cubic in any::<bool>(),
    ) {
        let falloff = if cubic { Falloff::CubicParabola } else { Falloff::SoftObject };
        let (fa, fb) = (Box::new(blobs(&a, falloff)), Box::new(blobs(&b, falloff)));
        let field: Box<dyn Field> = match op {
            0 => fa,
            1 => Box::new(FieldCsg::new(SetOp::Union, fa, fb)),
            2 => Box::new(FieldCsg::new(SetOp::Intersection, fa, fb)),
            _ => Box::new(FieldCsg::new(SetOp::Difference, fa, fb)),
        };
        let options = MarchingOptions {
            resolution,
            placement: if midpoints { Placement::Midpoint } else { Placement::Interpolated },
            ..MarchingOptions::default()
        };
        // An empty field is refused the same way by both.
        match SampleGrid::try_sample(field.as_ref(), resolution) {
            Ok(_) => {
                assert_same_as_whole_grid(field.as_ref(), &options);
            }
            Err(e) => prop_assert_eq!(try_mesh(field.as_ref(), &options).unwrap_err(), e),
        }
    }
}
