//! Octree cells of solids: exact `On` cells, one classification per region,
//! and certified volume intervals that hold closed-form volumes.

use std::path::Path;

use wingedge::cells::{CellsError, Label, MAX_DEPTH, Octree};
use wingedge::csg::Stats;
use wingedge::glam::DVec3;
use wingedge::io::read_obj;
use wingedge::mesh::{PolygonSoup, Solid, builders};

fn fixture(name: &str) -> Solid {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/valid")
        .join(name);
    Solid::try_from_soup(&read_obj(&path).unwrap()).unwrap()
}

fn assert_holds(tree: &Octree, volume: f64, what: &str) {
    let (low, high) = tree.try_volume_bounds().unwrap();
    assert!(
        low <= volume && volume <= high,
        "{what}: {volume} not in [{low}, {high}]"
    );
}

#[test]
fn intervals_hold_closed_form_volumes_and_shrink_with_depth() {
    let phi = (1.0 + 5f64.sqrt()) / 2.0;
    let ico = |r: f64| 5.0 / 12.0 * (3.0 + 5f64.sqrt()) * (2.0 * r).powi(3);
    let cases: Vec<(&str, Solid, f64)> = vec![
        ("cube", builders::cube(), 8.0),
        ("tetrahedron", builders::tetrahedron(), 8.0 / 3.0),
        ("L-prism", builders::l_prism(), 3.0),
        ("icosahedron", builders::icosahedron(), ico(1.0)),
        (
            "dodecahedron",
            builders::dodecahedron(),
            (15.0 + 7.0 * 5f64.sqrt()) / 4.0 * (2.0 / phi).powi(3),
        ),
        ("torus", fixture("torus_genus1.obj"), 8.0),
        ("double torus", fixture("double_torus_genus2.obj"), 13.0),
        (
            "hollow ball",
            fixture("hollow_ball.obj"),
            ico(2.0) - ico(1.0),
        ),
    ];
    for (name, solid, volume) in cases {
        let mut width = f64::INFINITY;
        let mut first = None;
        for depth in [2, 3, 5] {
            let tree = Octree::classify(&solid, depth).unwrap();
            assert_holds(&tree, volume, name);
            let (low, high) = tree.try_volume_bounds().unwrap();
            assert!(
                high - low <= width,
                "{name}: the interval grows at depth {depth}"
            );
            width = high - low;
            first.get_or_insert(width);
            // On cells only at the finest depth; leaves tile the root cube.
            let (_, side) = tree.root();
            let covered: f64 = tree
                .leaves()
                .iter()
                .map(|c| (side / f64::from(1u32 << c.depth)).powi(3))
                .sum();
            assert_eq!(covered, side.powi(3), "{name}");
            assert!(
                tree.leaves()
                    .iter()
                    .all(|c| c.label != Label::On || c.depth == depth)
            );
        }
        // The On cells cover the surface: about half the width per level.
        let first = first.expect("three depths");
        assert!(
            width < first / 2.0,
            "{name}: width {width} at depth 5, {first} at 2"
        );
    }
}

#[test]
fn one_classification_per_region_not_per_cell() {
    // The hollow ball: outside, the shell's inside and the cavity are three
    // regions, however many cells they hold.
    let tree = Octree::classify(&fixture("hollow_ball.obj"), 5).unwrap();
    assert_eq!(tree.regions(), 3, "{:?}", tree.counts());
    let inside: u64 = tree.counts().iter().map(|c| c.inside).sum();
    let outside: u64 = tree.counts().iter().map(|c| c.outside).sum();
    assert!(inside > 100 && outside > 100);
    // A cube centred on a cell corner: every cell is In, Out or On as its
    // position says, checked cell by cell against the closed form.
    let solid = builders::cuboid(DVec3::splat(-0.75), DVec3::splat(0.75)).unwrap();
    let tree = Octree::classify(&solid, 5).unwrap();
    for c in tree.leaves() {
        let b = tree.cell_box(c.depth, c.x, c.y, c.z);
        let want = if b.min.cmpge(DVec3::splat(-0.75)).all()
            && b.max.cmple(DVec3::splat(0.75)).all()
        {
            if b.min.cmpgt(DVec3::splat(-0.75)).all() && b.max.cmplt(DVec3::splat(0.75)).all() {
                Label::In
            } else {
                Label::On
            }
        } else if b.max.cmplt(DVec3::splat(-0.75)).any() || b.min.cmpgt(DVec3::splat(0.75)).any() {
            Label::Out
        } else {
            Label::On
        };
        assert_eq!(c.label, want, "{c:?} {b:?}");
    }
}

#[test]
fn the_dense_array_matches_the_leaves() {
    let tree = Octree::classify(&builders::l_prism(), 4).unwrap();
    let dense = tree.dense().unwrap();
    let n = 16usize;
    assert_eq!(dense.len(), n * n * n);
    let count = |v: u8| dense.iter().filter(|&&x| x == v).count() as u64;
    let finest = |label: Label| -> u64 {
        tree.leaves()
            .iter()
            .filter(|c| c.label == label)
            .map(|c| 1u64 << (3 * (4 - c.depth)))
            .sum()
    };
    assert_eq!(count(2), finest(Label::In));
    assert_eq!(count(1), finest(Label::On));
    assert_eq!(count(0), finest(Label::Out));
}

#[test]
fn bad_requests_are_refused() {
    let cube = builders::cube();
    assert_eq!(
        Octree::classify(&cube, MAX_DEPTH + 1).unwrap_err(),
        CellsError::TooDeep {
            depth: MAX_DEPTH + 1,
            limit: MAX_DEPTH
        }
    );
    assert!(matches!(
        Octree::classify(&cube, 10).unwrap().dense(),
        Err(CellsError::TooDeep { .. })
    ));
    let open = PolygonSoup::new(
        vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
        [[0, 2, 1], [0, 1, 3], [0, 3, 2]],
    );
    let open = Solid::try_from_soup(&open).unwrap();
    assert_eq!(
        Octree::classify(&open, 3).unwrap_err(),
        CellsError::NotClosed(3)
    );
    // Depth 0 over a box around the origin: one On cell holding it.
    let root = Octree::classify(&cube, 0).unwrap();
    assert_eq!(root.leaves().len(), 1);
    assert_eq!(root.leaves()[0].label, Label::On);
    assert_holds(&root, 8.0, "cube at depth 0");
    let far = builders::cuboid(DVec3::splat(1e50), DVec3::splat(1.5e50)).unwrap();
    assert!(Octree::classify(&far, 3).is_ok());
    let mut huge = builders::cube().to_soup();
    for p in &mut huge.positions {
        *p *= 1e308;
    }
    let huge = Solid::try_from_soup(&huge).unwrap();
    assert!(matches!(
        Octree::classify(&huge, 3),
        Err(CellsError::OutOfRange { .. })
    ));
}

fn scene(name: &str) -> wingedge::scene::Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/scenes")
        .join(name);
    wingedge::scene::Scene::from_file(&path).unwrap()
}

/// Every `In` or `Out` leaf's centre classifies the same way against the
/// tree.
fn assert_centres_agree(csg: &wingedge::csg::Csg, tree: &Octree, what: &str) {
    use wingedge::csg::Containment;
    let mut stats = Stats::default();
    for c in tree.leaves() {
        let b = tree.cell_box(c.depth, c.x, c.y, c.z);
        let got = csg.classify_point(b.center(), &mut stats);
        match c.label {
            Label::In => assert_eq!(got, Containment::Inside, "{what}: {c:?}"),
            Label::Out => assert_eq!(got, Containment::Outside, "{what}: {c:?}"),
            Label::On => {}
        }
    }
}

#[test]
fn cells_of_the_drilled_cube_hold_its_closed_form_volume() {
    // 8 minus three orthogonal cylinders of radius ½ through the cube:
    // 3 · (π/2) − 3 · (2/3) (bicylinders, 16 r³/3) + (2 − √2) (the
    // tricylinder, 8 (2 − √2) r³).
    let exact = 8.0 - 1.5 * std::f64::consts::PI + 2f64.sqrt();
    let drilled = scene("drilled_cube.json");
    let mut width = f64::INFINITY;
    for depth in 2..=7 {
        let tree = Octree::classify_csg(&drilled.csg, depth, &mut Stats::default()).unwrap();
        assert_holds(&tree, exact, &format!("drilled cube, depth {depth}"));
        let (low, high) = tree.try_volume_bounds().unwrap();
        assert!(high - low < width, "depth {depth}: {low} {high}");
        width = high - low;
        if depth <= 5 {
            assert_centres_agree(&drilled.csg, &tree, "drilled cube");
        }
    }
    assert!(width / exact < 0.25, "{width}");
}

#[test]
fn cells_of_scenes_hold_their_volumes_and_agree_with_classify() {
    // The many-leaves plate: boxes and spheres that only touch the plate
    // and each other, so the union's volume is the sum of the leaves'.
    let many = scene("many_leaves.json");
    let sum: f64 = many
        .csg
        .leaves()
        .iter()
        .map(|l| l.primitive.exact_volume().unwrap())
        .sum();
    for depth in [3, 5, 6] {
        let tree = Octree::classify_csg(&many.csg, depth, &mut Stats::default()).unwrap();
        assert_holds(&tree, sum, &format!("many leaves, depth {depth}"));
    }
    // Only the work a cell calls for: 101 leaves, yet about one leaf box
    // test per cell (the others are culled by the tree's bounds), and no
    // point classification (boxes and spheres answer inside or outside).
    let mut stats = Stats::default();
    let tree = Octree::classify_csg(&many.csg, 5, &mut stats).unwrap();
    let visited = tree.leaves().len() as u64;
    assert!(
        stats.primitive_cell_tests < 2 * visited && stats.culled_subtrees > 10 * visited,
        "{stats} for {visited} leaves"
    );
    assert_eq!(stats.primitive_point_tests, 0);
    assert_centres_agree(&many.csg, &tree, "many");
    // Scenes without a closed form: the ray-integrated volume (close to
    // the exact one, far closer than the interval's width) lies inside.
    for name in [
        "platonic.json",
        "mesh_cut.json",
        "turned_part.json",
        "blobby.json",
    ] {
        let s = scene(name);
        let tree = Octree::classify_csg(&s.csg, 4, &mut Stats::default()).unwrap();
        assert_centres_agree(&s.csg, &tree, name);
        let mut stats = Stats::default();
        let tree = Octree::classify_csg(&s.csg, 6, &mut stats).unwrap();
        if name == "turned_part.json" {
            // Polyhedral leaves: a side learnt on a cell serves its
            // face neighbours among its siblings, so far fewer points are
            // classified than there are cells.
            let cells = tree.leaves().len() as u64;
            assert!(
                0 < stats.primitive_point_tests && stats.primitive_point_tests * 4 < cells,
                "{stats} for {cells} leaves"
            );
        }
        let (low, high) = tree.try_volume_bounds().unwrap();
        let estimate = s.csg.try_volume(0.03).unwrap().volume;
        assert!(
            0.0 < low && low < estimate && estimate < high,
            "{name}: {estimate} not in [{low}, {high}]"
        );
    }
}

/// The In shell validates as a solid whose volume is `V_in` plus the
/// filled sub-cells exactly, within the certified interval.
fn assert_valid_shell(tree: &Octree, what: &str) -> wingedge::cells::InShell {
    use wingedge::validate::{Options, Validity, validate_soup};
    let shell = tree.in_shell().unwrap();
    let report = validate_soup(&shell.soup, None, &Options::default()).unwrap();
    assert_eq!(
        report.validity,
        Validity::ValidSolid,
        "{what}: {:?} {:#?}",
        report.not_built,
        &report.violations[..report.violations.len().min(5)]
    );
    let solid = Solid::try_from_soup(&shell.soup).unwrap();
    assert_eq!(solid.volume(), shell.volume, "{what}");
    let (low, high) = tree.try_volume_bounds().unwrap();
    assert!(low <= shell.volume && shell.volume <= high, "{what}");
    assert_eq!(shell.filled == 0, shell.volume == low, "{what}");
    shell
}

/// A tree over `[0, 8]³` (unit cells at depth 3) of the box cut by the
/// given half-spaces.
fn cut_box(halfspaces: &[(DVec3, DVec3)]) -> wingedge::csg::Csg {
    use wingedge::csg::{AxisBox, Csg, CsgExpr, HalfSpace};
    let mut parts = vec![CsgExpr::leaf(
        AxisBox::try_new(DVec3::ZERO, DVec3::splat(8.0)).unwrap(),
    )];
    for &(point, normal) in halfspaces {
        parts.push(CsgExpr::leaf(HalfSpace::try_new(point, normal).unwrap()));
    }
    Csg::try_new(CsgExpr::Intersection(parts)).unwrap()
}

#[test]
fn the_in_shell_is_a_valid_solid_within_the_certified_interval() {
    let tree = Octree::classify(&fixture("torus_genus1.obj"), 5).unwrap();
    let shell = assert_valid_shell(&tree, "torus");
    assert!(shell.soup.polygons.len() > 100);
    let tree =
        Octree::classify_csg(&scene("drilled_cube.json").csg, 5, &mut Stats::default()).unwrap();
    assert_valid_shell(&tree, "drilled cube");
    let tree = Octree::classify(&fixture("hollow_ball.obj"), 5).unwrap();
    assert_valid_shell(&tree, "hollow ball");
}

#[test]
fn in_cells_touching_along_an_edge_or_at_a_corner_give_a_valid_solid() {
    // The slab ½ < y − x < 3½ holds whole unit cells only where
    // y − x = 2: a staircase of cells touching along edges parallel to z.
    let slab = cut_box(&[
        (DVec3::new(0.0, 3.5, 0.0), DVec3::new(-1.0, 1.0, 0.0)),
        (DVec3::new(0.0, 0.5, 0.0), DVec3::new(1.0, -1.0, 0.0)),
    ]);
    let tree = Octree::classify_csg(&slab, 3, &mut Stats::default()).unwrap();
    let inside: Vec<_> = tree
        .leaves()
        .iter()
        .filter(|c| c.label == Label::In)
        .collect();
    assert!(!inside.is_empty());
    assert!(inside.iter().all(|c| c.y == c.x + 2), "{inside:?}");
    let shell = assert_valid_shell(&tree, "edge contacts");
    assert!(shell.filled > 0);
    // One shell: the staircase joined, no cavity added.
    let solid = Solid::try_from_soup(&shell.soup).unwrap();
    assert_eq!(solid.shells().len(), 1);
    // Two such slabs: cells (i, i + 2, i + 2), touching only at corners.
    let tube = cut_box(&[
        (DVec3::new(0.0, 3.5, 0.0), DVec3::new(-1.0, 1.0, 0.0)),
        (DVec3::new(0.0, 0.5, 0.0), DVec3::new(1.0, -1.0, 0.0)),
        (DVec3::new(0.0, 0.0, 3.5), DVec3::new(-1.0, 0.0, 1.0)),
        (DVec3::new(0.0, 0.0, 0.5), DVec3::new(1.0, 0.0, -1.0)),
    ]);
    let tree = Octree::classify_csg(&tube, 3, &mut Stats::default()).unwrap();
    let inside: Vec<_> = tree
        .leaves()
        .iter()
        .filter(|c| c.label == Label::In)
        .collect();
    assert!(inside.len() >= 2, "{inside:?}");
    assert!(
        inside.iter().all(|c| c.y == c.x + 2 && c.z == c.x + 2),
        "{inside:?}"
    );
    let shell = assert_valid_shell(&tree, "corner contacts");
    assert!(shell.filled > 0);
}

#[test]
fn in_shells_of_random_cut_boxes_are_valid_solids() {
    use wingedge::csg::{AxisBox, Csg, CsgExpr, HalfSpace, Sphere};
    // A small deterministic generator (xorshift), so failures replay.
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let (mut repaired, mut empty) = (0, 0);
    for trial in 0..300 {
        let mut parts = Vec::new();
        for _ in 0..4 {
            let a = DVec3::new(next(), next(), next()) * 6.0;
            let b = a + DVec3::new(next(), next(), next()) * 4.0 + DVec3::splat(0.5);
            let normal = DVec3::new(next() - 0.5, next() - 0.5, next() - 0.5);
            let piece = CsgExpr::leaf(AxisBox::try_new(a, b).unwrap()).intersection(CsgExpr::leaf(
                HalfSpace::try_new((a + b) * 0.5, normal).unwrap(),
            ));
            parts.push(piece);
        }
        parts.push(CsgExpr::leaf(
            Sphere::try_new(DVec3::new(next(), next(), next()) * 8.0, 1.0 + next()).unwrap(),
        ));
        let csg = Csg::try_new(CsgExpr::Union(parts)).unwrap();
        let tree = Octree::classify_csg(&csg, 4 + trial % 2, &mut Stats::default()).unwrap();
        if tree.try_volume_bounds().unwrap().0 == 0.0 {
            // No In cell: no faces.
            assert!(tree.in_shell().unwrap().soup.polygons.is_empty());
            empty += 1;
            continue;
        }
        let shell = assert_valid_shell(&tree, &format!("trial {trial}"));
        repaired += shell.filled;
    }
    assert!(repaired > 0, "no trial needed a repair");
    assert!(empty < 60, "{empty} trials without In cells");
}
