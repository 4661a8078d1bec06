//! Reconstructions of generated point sets, checked with code that does not trust the library.

mod common;

use common::*;
use dbrg::{BoundaryMean, Params, Points};

#[test]
fn fibonacci_sphere_is_a_closed_oriented_genus_zero_surface() {
    let points = fibonacci_sphere(400);
    let mesh = dbrg::reconstruct(&points, &Params::default()).expect("reconstruct");
    let triangles = mesh.triangles();
    assert_eq!(triangles.len(), 2 * points.len() - 4);
    assert_eq!(manifold_problems(triangles, false), Vec::<String>::new());
    assert_eq!(euler_characteristic(triangles), 2);
    assert!(signed_volume6(&points, triangles) > 0.0, "a closed surface faces outward");
    assert_eq!(mesh.boundary_loop_count(), 0);
    assert_eq!(mesh.boundary_loops().count(), 0);
    assert!(mesh.boundary_loop(0).is_none());
    assert_eq!(mesh.point_count() as usize, points.len());

    let stats = mesh.stats();
    assert_eq!(stats.struct_size, std::mem::size_of::<dbrg::Stats>());
    assert_eq!(stats.input_points as usize, points.len());
    assert_eq!(stats.vertices_used as usize, points.len());
    assert_eq!(stats.triangles as usize, triangles.len());
    assert_eq!(stats.boundary_edges, 0);
    assert!(stats.tetrahedra > 0 && stats.seconds_total > 0.0 && stats.peak_bytes > 0);
}

#[test]
fn a_tight_boundary_factor_warns_and_the_default_does_not() {
    let points = fibonacci_sphere(400);
    assert_eq!(dbrg::reconstruct(&points, &Params::default()).expect("reconstruct").warning(), None);
    let mut tight = Params::default();
    tight.boundary_factor = 1.001;
    let mesh = dbrg::reconstruct(&points, &tight).expect("reconstruct");
    let warning = mesh.warning().expect("a warning");
    assert!(warning.starts_with("warning: only"), "{}", warning);
    assert!(warning.contains("boundary_factor"), "{}", warning);
}

#[test]
fn f32_input_gives_a_closed_sphere() {
    let points: Vec<[f32; 3]> = fibonacci_sphere(400).iter().map(|p| [p[0] as f32, p[1] as f32, p[2] as f32]).collect();
    let mesh = dbrg::reconstruct(&points, &Params::default()).expect("reconstruct f32");
    assert_eq!(manifold_problems(mesh.triangles(), false), Vec::<String>::new());
    assert_eq!(euler_characteristic(mesh.triangles()), 2);
}

#[test]
fn slices_arrays_and_strided_data_give_the_same_triangles() {
    let points = fibonacci_sphere(300);
    let reference = canonical(dbrg::reconstruct(&points, &Params::default()).unwrap().triangles());

    let slice: &[[f64; 3]] = &points[..];
    assert_eq!(canonical(dbrg::reconstruct(slice, &Params::default()).unwrap().triangles()), reference);

    // Positions interleaved with normals (NaN, never read): a stride of 6 scalars.
    let interleaved: Vec<f64> = points.iter().flat_map(|p| vec![p[0], p[1], p[2], f64::NAN, f64::NAN, f64::NAN]).collect();
    let strided = Points::strided(&interleaved, 6).unwrap();
    assert_eq!(strided.len(), points.len());
    assert_eq!(canonical(dbrg::reconstruct(strided, &Params::default()).unwrap().triangles()), reference);

    // A #[repr(C)] vertex struct read through its position field.
    #[repr(C)]
    struct Vertex {
        id: u64,
        position: [f64; 3],
    }
    let vertices: Vec<Vertex> = points.iter().enumerate().map(|(i, p)| Vertex { id: i as u64, position: *p }).collect();
    assert_eq!(vertices[1].id, 1);
    let raw = unsafe {
        Points::from_raw_parts(vertices[0].position.as_ptr(), vertices.len(), std::mem::size_of::<Vertex>())
    };
    assert_eq!(canonical(dbrg::reconstruct(raw, &Params::default()).unwrap().triangles()), reference);

    let small = [[0.0f64, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let tetrahedron = dbrg::reconstruct(&small, &Params::default()).unwrap();
    assert_eq!(tetrahedron.triangles().len(), 4);
    assert_eq!(manifold_problems(tetrahedron.triangles(), false), Vec::<String>::new());
}

#[test]
fn open_patch_keeps_its_border_as_a_boundary_loop() {
    let points = paraboloid_patch(14);
    let mesh = dbrg::reconstruct(&points, &Params::default()).unwrap();
    assert_eq!(manifold_problems(mesh.triangles(), true), Vec::<String>::new());
    assert!(mesh.boundary_loop_count() >= 1);
    let directed: std::collections::HashSet<(u32, u32)> =
        mesh.triangles().iter().flat_map(|&[a, b, c]| vec![(a, b), (b, c), (c, a)]).collect();
    let mut loop_edges = 0;
    for boundary in mesh.boundary_loops() {
        for (k, &a) in boundary.iter().enumerate() {
            let b = boundary[(k + 1) % boundary.len()];
            assert!(directed.contains(&(a, b)), "a loop step is an edge its triangle traverses that way");
            assert!(!directed.contains(&(b, a)), "and no triangle lies on its other side");
            loop_edges += 1;
        }
    }
    assert_eq!(loop_edges, mesh.stats().boundary_edges);
}

#[test]
fn params_default_to_the_library_and_every_field_reaches_it() {
    let params = Params::default();
    assert!((params.sliver_angle - 5.0 * std::f64::consts::PI / 6.0).abs() < 1e-12);
    assert!(params.fill_holes);
    let raw = params.to_raw();
    assert_eq!(raw.struct_size, std::mem::size_of::<dbrg::sys::dbrg_params>(), "the Rust struct has the C size");

    let mut custom = Params::default();
    custom.sliver_angle = 2.5;
    custom.boundary_factor = 0.0;
    custom.boundary_mean = BoundaryMean::Global;
    custom.fill_holes = false;
    custom.max_hole_edges = 12;
    custom.max_components = 2;
    custom.threads = 2;
    let raw = custom.to_raw();
    assert_eq!(
        (raw.sliver_angle, raw.boundary_factor, raw.boundary_mean, raw.fill_holes, raw.max_hole_edges),
        (2.5, 0.0, dbrg::sys::DBRG_BOUNDARY_MEAN_GLOBAL, 0, 12)
    );
    assert_eq!((raw.max_components, raw.backend, raw.threads), (2, dbrg::sys::DBRG_BACKEND_BUILTIN, 2));
    let mesh = dbrg::reconstruct(&fibonacci_sphere(300), &custom).unwrap();
    assert_eq!(manifold_problems(mesh.triangles(), false), Vec::<String>::new());
}

#[test]
fn meshes_move_between_threads() {
    let handles: Vec<_> = (0..3)
        .map(|k| std::thread::spawn(move || dbrg::reconstruct(&fibonacci_sphere(200 + 50 * k), &Params::default()).unwrap()))
        .collect();
    for (k, handle) in handles.into_iter().enumerate() {
        let mesh = handle.join().unwrap();
        assert_eq!(mesh.triangles().len(), 2 * (200 + 50 * k) - 4);
    }
}

#[test]
fn the_linked_library_is_the_version_this_crate_declares() {
    assert_eq!(
        dbrg::library_version(),
        (dbrg::sys::DBRG_VERSION_MAJOR, dbrg::sys::DBRG_VERSION_MINOR, dbrg::sys::DBRG_VERSION_PATCH)
    );
    assert_eq!(dbrg::library_version_string(), dbrg::sys::DBRG_VERSION_STRING);
    assert_eq!(dbrg::sys::DBRG_VERSION_STRING, env!("CARGO_PKG_VERSION"));
}

#[test]
fn the_faces_hole_filling_made_are_flagged() {
    // A sphere without its points around one pole: growing leaves a hole there that filling closes.
    let points: Vec<[f64; 3]> = fibonacci_sphere(1000).into_iter().filter(|p| p[2] < 0.9).collect();
    let filled = dbrg::reconstruct(&points, &Params::default()).expect("reconstruct");
    let mut no_filling = Params::default();
    no_filling.fill_holes = false;
    let unfilled = dbrg::reconstruct(&points, &no_filling).expect("reconstruct");
    assert!(filled.stats().holes_filled > 0);
    for mesh in [&filled, &unfilled] {
        assert_eq!(mesh.face_flags().len(), mesh.triangles().len());
        assert!(mesh.face_flags().iter().all(|&f| f & !dbrg::FACE_FILLED == 0));
    }
    assert!(unfilled.face_flags().iter().all(|&f| f == 0));
    let flagged: Vec<[u32; 3]> = filled
        .triangles()
        .iter()
        .zip(filled.face_flags())
        .filter(|(_, &f)| f & dbrg::FACE_FILLED != 0)
        .map(|(t, _)| *t)
        .collect();
    assert!(!flagged.is_empty());
    // The flagged faces are over the hole: none is one growing made.
    assert!(canonical(&flagged).is_disjoint(&canonical(unfilled.triangles())));
}
