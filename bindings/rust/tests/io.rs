//! The dbrg program's readers and writers through libdbrg_io: a written mesh reads back as its vertices and
//! normals, a PLY's vertex properties come with their names and types, and failures name the problem.

mod common;

use std::fs;
use std::path::PathBuf;

use common::{fibonacci_sphere, paraboloid_patch};
use dbrg::{AttributeValues, Params, Points, Status};

/// A folder of its own for one test, removed when dropped.
struct Scratch(PathBuf);

impl Scratch {
    fn new(test: &str) -> Scratch {
        let dir = std::env::temp_dir().join(format!("dbrg-rust-io-{}-{}", std::process::id(), test));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).expect("create a scratch folder");
        Scratch(dir)
    }

    fn path(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = fs::remove_dir_all(&self.0);
    }
}

fn attribute<'a>(attributes: &'a [dbrg::Attribute], name: &str) -> &'a AttributeValues {
    &attributes.iter().find(|a| a.name == name).unwrap_or_else(|| panic!("no attribute {}", name)).values
}

#[test]
fn a_mesh_written_with_normals_reads_back_as_its_vertices_and_normals() {
    let scratch = Scratch::new("round-trip");
    let points = fibonacci_sphere(300);
    let mesh = dbrg::reconstruct(&points, &Params::default()).expect("reconstruct");
    let normals = mesh.vertex_normals(&points).expect("normals");
    assert_eq!(normals.len(), points.len());
    for (p, n) in points.iter().zip(&normals) {
        let length = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        assert!((length - 1.0).abs() < 1e-5, "a unit normal, not {:?}", n);
        let outward = p[0] * n[0] as f64 + p[1] * n[1] as f64 + p[2] * n[2] as f64;
        assert!(outward > 0.9, "the normal at {:?} points outward, not {:?}", p, n);
    }

    let path = scratch.path("sphere.ply");
    mesh.write(&path, &points, true).expect("write");
    let (read, attributes) = dbrg::read_points(&path).expect("read back");
    assert_eq!(read, points, "binary PLY keeps every double");
    let names: Vec<&str> = attributes.iter().map(|a| a.name.as_str()).collect();
    assert_eq!(names, ["nx", "ny", "nz"]);
    for (axis, name) in ["nx", "ny", "nz"].iter().enumerate() {
        let expected: Vec<f32> = normals.iter().map(|n| n[axis]).collect();
        assert_eq!(attribute(&attributes, name), &AttributeValues::F32(expected));
    }

    mesh.write(scratch.path("plain.ply"), &points, false).expect("write without normals");
    let (read, attributes) = dbrg::read_points(scratch.path("plain.ply")).expect("read back");
    assert_eq!((read, attributes), (points.clone(), vec![]));

    for name in ["sphere.obj", "sphere.off", "sphere.xyz"] {
        mesh.write(scratch.path(name), &points, true).expect(name);
        assert_eq!(dbrg::read_points(scratch.path(name)).expect(name).0, points, "{}", name);
    }
}

#[test]
fn write_takes_the_points_as_reconstruct_does() {
    let scratch = Scratch::new("point-types");
    let points = paraboloid_patch(12);
    let single: Vec<[f32; 3]> = points.iter().map(|p| [p[0] as f32, p[1] as f32, p[2] as f32]).collect();
    let mesh = dbrg::reconstruct(&single, &Params::default()).expect("reconstruct");
    mesh.write(scratch.path("single.ply"), &single, false).expect("write");
    let widened: Vec<[f64; 3]> = single.iter().map(|p| [p[0] as f64, p[1] as f64, p[2] as f64]).collect();
    assert_eq!(dbrg::read_points(scratch.path("single.ply")).expect("read").0, widened);

    // Positions interleaved with a fourth value: the same vertices.
    let interleaved: Vec<f64> = points.iter().flat_map(|p| [p[0], p[1], p[2], -1.0]).collect();
    let mesh = dbrg::reconstruct(&points, &Params::default()).expect("reconstruct");
    let strided = Points::strided(&interleaved, 4).expect("stride 4");
    assert_eq!(mesh.vertices(strided).expect("vertices"), points);
    assert_eq!(mesh.vertex_normals(strided).expect("normals"), mesh.vertex_normals(&points).expect("normals"));

    let error = mesh.write(scratch.path("short.ply"), &points[1..], true).expect_err("one point short");
    assert_eq!(error.status, Status::InvalidArgument);
    assert!(error.message.contains("points it was reconstructed from"), "{}", error.message);
    assert!(!scratch.path("short.ply").exists());
}

#[test]
fn vertex_normals_of_a_small_mesh() {
    // A unit square in z = 0, counter-clockwise seen from +z, and a vertex no triangle uses.
    let vertices = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0], [5.0, 5.0, 5.0]];
    let normals = dbrg::vertex_normals(&vertices, &[[0, 1, 2], [0, 2, 3]]).expect("normals");
    assert_eq!(&normals[..4], &[[0.0, 0.0, 1.0]; 4]);
    assert_eq!(normals[4], [0.0; 3]);
    assert_eq!(dbrg::vertex_normals(&[], &[]).expect("nothing"), Vec::<[f32; 3]>::new());
    let error = dbrg::vertex_normals(&vertices, &[[0, 1, 2], [0, 2, 5]]).expect_err("index past the end");
    assert_eq!(error.status, Status::InvalidArgument);
    assert!(error.message.contains("triangle 1"), "{}", error.message);
}

#[test]
fn a_coloured_ply_gives_its_properties_with_their_names_and_types() {
    let scratch = Scratch::new("coloured");
    let path = scratch.path("coloured.ply");
    fs::write(
        &path,
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\n\
         property uchar red\nproperty uchar green\nproperty uchar blue\nproperty ushort intensity\n\
         property float confidence\nproperty int label\nproperty float nx\nproperty float ny\nproperty float nz\n\
         element face 1\nproperty list uchar int vertex_indices\nend_header\n\
         0.5 -1 2 255 0 7 65535 0.25 -4 0 0 1\n1 2 3 1 2 3 0 1 70000 0 1 0\n-4 5 6.5 9 8 7 300 -0.5 0 1 0 0\n3 0 1 2\n",
    )
    .expect("write the PLY");
    let (points, attributes) = dbrg::read_points(&path).expect("read");
    assert_eq!(points, [[0.5, -1.0, 2.0], [1.0, 2.0, 3.0], [-4.0, 5.0, 6.5]]);
    let names: Vec<&str> = attributes.iter().map(|a| a.name.as_str()).collect();
    assert_eq!(names, ["red", "green", "blue", "intensity", "confidence", "label", "nx", "ny", "nz"]);
    assert_eq!(attribute(&attributes, "red"), &AttributeValues::U8(vec![255, 1, 9]));
    assert_eq!(attribute(&attributes, "blue"), &AttributeValues::U8(vec![7, 3, 7]));
    assert_eq!(attribute(&attributes, "intensity"), &AttributeValues::U16(vec![65535, 0, 300]));
    assert_eq!(attribute(&attributes, "confidence"), &AttributeValues::F32(vec![0.25, 1.0, -0.5]));
    assert_eq!(attribute(&attributes, "label"), &AttributeValues::I32(vec![-4, 70000, 0]));
    assert_eq!(attribute(&attributes, "nz"), &AttributeValues::F32(vec![1.0, 0.0, 0.0]));
    for a in &attributes {
        assert_eq!(a.values.len(), points.len(), "{}", a.name);
    }
    assert_eq!(attribute(&attributes, "label").get(1), Some(70000.0));
    assert_eq!(attribute(&attributes, "label").get(3), None);
}

#[test]
fn failures_name_the_problem() {
    let scratch = Scratch::new("failures");
    let missing = scratch.path("missing.ply");
    let error = dbrg::read_points(&missing).expect_err("no such file");
    assert_eq!(error.status, Status::File);
    assert_eq!(error.status.name(), "DBRG_IO_ERR_FILE");
    assert!(error.message.contains("missing.ply"), "{}", error.message);

    let error = dbrg::read_points(scratch.path("scan.laz")).expect_err("compressed");
    assert_eq!(error.status, Status::InvalidArgument);
    assert!(error.message.contains("decompress"), "{}", error.message);
    let error = dbrg::read_points(scratch.path("points.dat")).expect_err("unknown extension");
    assert_eq!(error.status, Status::InvalidArgument);
    assert!(error.message.contains("unknown file type"), "{}", error.message);

    let truncated = scratch.path("truncated.ply");
    let header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
    fs::write(&truncated, format!("{}end_header\n0 0 0\n", header)).unwrap();
    assert_eq!(dbrg::read_points(&truncated).expect_err("truncated").status, Status::File);

    let vertices = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let error =
        dbrg::write_mesh(scratch.path("no-such-folder/m.ply"), &vertices, &[[0, 1, 2]], None).expect_err("no folder");
    assert_eq!(error.status, Status::File);
    assert!(error.message.contains("no-such-folder"), "{}", error.message);
    let error =
        dbrg::write_mesh(scratch.path("m.las"), &vertices, &[[0, 1, 2]], None).expect_err("not a written format");
    assert_eq!(error.status, Status::InvalidArgument);
    let error = dbrg::write_mesh(scratch.path("m.ply"), &vertices, &[[0, 1, 3]], None).expect_err("index past the end");
    assert_eq!(error.status, Status::InvalidArgument);
    assert!(error.message.contains("triangle 0"), "{}", error.message);
    let error = dbrg::write_mesh(scratch.path("m.ply"), &vertices, &[[0, 1, 2]], Some(&[[0.0, 0.0, 1.0]]))
        .expect_err("one normal");
    assert_eq!(error.status, Status::InvalidArgument);
    assert!(!scratch.path("m.ply").exists(), "nothing is written on failure");
}

#[test]
fn points_without_triangles_are_written_alone() {
    let scratch = Scratch::new("points-only");
    let points = fibonacci_sphere(20);
    dbrg::write_mesh(scratch.path("cloud.xyz"), &points, &[], None).expect("write");
    assert_eq!(dbrg::read_points(scratch.path("cloud.xyz")).expect("read").0, points);
}
