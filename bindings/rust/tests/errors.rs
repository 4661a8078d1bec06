//! Bad input gives an Error with the status and the library's message.

mod common;

use common::fibonacci_sphere;
use dbrg::{Params, Points, Status};

fn error_of(points: &[[f64; 3]], params: &Params) -> dbrg::Error {
    dbrg::reconstruct(points, params).expect_err("the call should fail")
}

#[test]
fn nan_names_the_point() {
    let mut points = fibonacci_sphere(200);
    points[137][1] = f64::NAN;
    let error = error_of(&points, &Params::default());
    assert_eq!(error.status, Status::NonFiniteInput);
    assert!(error.message.contains("137") && error.message.contains("NaN"), "{}", error.message);
    assert_eq!(error.status.name(), "DBRG_ERR_NON_FINITE_INPUT");
    assert!(error.to_string().contains("DBRG_ERR_NON_FINITE_INPUT"));
    let boxed: Box<dyn std::error::Error> = Box::new(error);
    assert!(boxed.to_string().contains("137"));
}

#[test]
fn infinity_in_f32_names_the_point() {
    let mut points: Vec<[f32; 3]> = fibonacci_sphere(100).iter().map(|p| [p[0] as f32, p[1] as f32, p[2] as f32]).collect();
    points[42][2] = f32::INFINITY;
    let error = dbrg::reconstruct(&points, &Params::default()).unwrap_err();
    assert_eq!(error.status, Status::NonFiniteInput);
    assert!(error.message.contains("42"), "{}", error.message);
}

#[test]
fn too_few_points() {
    let points = fibonacci_sphere(3);
    assert_eq!(error_of(&points, &Params::default()).status, Status::TooFewPoints);
    let repeated: Vec<[f64; 3]> = (0..12).map(|i| points[i % 3]).collect();
    assert_eq!(error_of(&repeated, &Params::default()).status, Status::TooFewPoints);
    assert_eq!(error_of(&[], &Params::default()).status, Status::TooFewPoints);
}

#[test]
fn coplanar_and_collinear_points() {
    // Coplanar points are a flat surface, without tetrahedra.
    let plane: Vec<[f64; 3]> = (0..50).map(|i| [(i % 7) as f64, (i / 7) as f64 * 0.5, 0.25]).collect();
    assert!(!dbrg::reconstruct(&plane, &Params::default()).expect("a flat surface").triangles().is_empty());
    let error = dbrg::tetrahedralize(&plane, &Params::default()).expect_err("no tetrahedra");
    assert_eq!(error.status, Status::DegenerateInput);
    assert!(error.message.contains("coplanar"), "{}", error.message);
    let line: Vec<[f64; 3]> = (0..20).map(|i| [i as f64, 2.0 * i as f64, 3.0 * i as f64]).collect();
    assert_eq!(error_of(&line, &Params::default()).status, Status::DegenerateInput);
}

#[test]
fn out_of_range_parameters_are_named() {
    let points = fibonacci_sphere(100);
    let cases: [(&str, fn(&mut Params)); 4] = [
        ("sliver_angle", |p| p.sliver_angle = 1.0),
        ("boundary_factor", |p| p.boundary_factor = 0.5),
        ("max_hole_edges", |p| p.max_hole_edges = 2),
        ("max_components", |p| p.max_components = 0),
    ];
    for (name, change) in cases {
        let mut params = Params::default();
        change(&mut params);
        let error = error_of(&points, &params);
        assert_eq!(error.status, Status::InvalidParameter, "{}", name);
        assert!(error.message.contains(name), "{}: {}", name, error.message);
    }
}

#[test]
fn tetgen_works_or_says_it_is_not_built() {
    let mut params = Params::default();
    params.backend = dbrg::Backend::Tetgen;
    match dbrg::reconstruct(&fibonacci_sphere(200), &params) {
        Ok(mesh) => assert_eq!(mesh.triangles().len(), 396),
        Err(error) => assert_eq!(error.status, Status::Unsupported),
    }
}

#[test]
fn a_stride_shorter_than_a_point_is_refused() {
    let data = [0.0f64; 12];
    assert_eq!(Points::strided(&data, 2).unwrap_err().status, Status::InvalidArgument);
    let overlapping = unsafe { Points::from_raw_parts(data.as_ptr(), 4, 8) };
    let error = dbrg::reconstruct(overlapping, &Params::default()).unwrap_err();
    assert_eq!(error.status, Status::InvalidArgument);
    assert!(error.message.contains("stride"), "{}", error.message);
}

#[test]
fn validate_points_reports_without_computing() {
    let mut points = fibonacci_sphere(100);
    assert_eq!(dbrg::validate_points(&points), Ok(()));
    points[5][0] = f64::NEG_INFINITY;
    let error = dbrg::validate_points(&points).unwrap_err();
    assert_eq!(error.status, Status::NonFiniteInput);
    assert!(error.message.contains('5'), "{}", error.message);
}

#[test]
fn status_names_and_codes_round_trip() {
    for code in 1..=10u32 {
        let status = match code {
            1 => Status::InvalidArgument,
            2 => Status::InvalidParameter,
            3 => Status::NonFiniteInput,
            4 => Status::TooFewPoints,
            5 => Status::DegenerateInput,
            6 => Status::TooManyPoints,
            7 => Status::OutOfMemory,
            8 => Status::Cancelled,
            9 => Status::Unsupported,
            _ => Status::Internal,
        };
        assert_eq!(status.code(), code);
        assert!(status.name().starts_with("DBRG_ERR_"), "{}", status.name());
    }
    assert_eq!(Status::Other(999).name(), "DBRG_STATUS_UNKNOWN");
}
