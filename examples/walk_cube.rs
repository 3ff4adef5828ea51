//! Build a cube, walk its winged-edge adjacency, and print its measures.
//!
//! Run with `cargo run --example walk_cube`.

use wingedge::mesh::builders;

fn main() {
    let cube = builders::cube();
    cube.check_consistency()
        .expect("builders produce consistent solids");
    println!(
        "cube: V={} E={} F={} χ={} volume={} area={}",
        cube.vertex_count(),
        cube.edge_count(),
        cube.face_count(),
        cube.euler_characteristic(),
        cube.volume(),
        cube.surface_area()
    );
    let (v, vertex) = cube.vertices().next().expect("a cube has vertices");
    println!("vertex {v:?} at {}:", vertex.position);
    for w in cube.vertex_vertices(v) {
        println!("  joined to {}", cube.position(w));
    }
    println!("  faces around it: {}", cube.vertex_faces(v).count());
    let (f, face) = cube.faces().next().expect("a cube has faces");
    let plane = face.plane.expect("cube faces have area");
    println!("face {f:?}, outward normal {}:", plane.normal);
    for p in cube.face_vertices(f).map(|v| cube.position(v)) {
        println!("  corner {p}");
    }
    println!("  neighbours: {}", cube.face_neighbours(f).count());
}
