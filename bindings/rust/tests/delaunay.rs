//! tetrahedralize: orientation, adjacency and volume, checked here.

mod common;

use dbrg::{sys::DBRG_NO_NEIGHBOR, Params};

fn cube_points() -> Vec<[f64; 3]> {
    let mut points = Vec::new();
    for &x in &[0.0, 1.0] {
        for &y in &[0.0, 1.0] {
            for &z in &[0.0, 1.0] {
                points.push([x, y, z]);
            }
        }
    }
    let mut seed = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        0.02 + 0.96 * ((seed >> 11) as f64 / (1u64 << 53) as f64)
    };
    for _ in 0..150 {
        points.push([next(), next(), next()]);
    }
    points
}

fn orientation(p: &[[f64; 3]], t: &[u32; 4]) -> f64 {
    let [a, b, c, d] = [p[t[0] as usize], p[t[1] as usize], p[t[2] as usize], p[t[3] as usize]];
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let w = [d[0] - a[0], d[1] - a[1], d[2] - a[2]];
    u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0])
}

#[test]
fn tets_are_oriented_fill_the_cube_and_neighbour_each_other() {
    let points = cube_points();
    let result = dbrg::tetrahedralize(&points, &Params::default()).unwrap();
    let (tets, adjacency) = (result.tets(), result.adjacency());
    assert!(!tets.is_empty());
    assert_eq!(tets.len(), adjacency.len());
    assert_eq!(result.unique_point_count() as usize, points.len());
    // d on the side of (a, b, c) from which a, b, c appear clockwise: a negative triple product here.
    assert!(tets.iter().all(|t| orientation(&points, t) < 0.0));
    let volume: f64 = tets.iter().map(|t| -orientation(&points, t) / 6.0).sum();
    assert!((volume - 1.0).abs() < 1e-9, "{}", volume);
    let mut hull_faces = 0;
    for (t, neighbours) in adjacency.iter().enumerate() {
        for (f, &n) in neighbours.iter().enumerate() {
            if n == DBRG_NO_NEIGHBOR {
                hull_faces += 1;
                continue;
            }
            let back = adjacency[n as usize].iter().position(|&m| m as usize == t).expect("adjacency is mutual");
            let mut face: Vec<u32> = (0..4).filter(|&k| k != f).map(|k| tets[t][k]).collect();
            let mut other: Vec<u32> = (0..4).filter(|&k| k != back).map(|k| tets[n as usize][k]).collect();
            face.sort_unstable();
            other.sort_unstable();
            assert_eq!(face, other);
        }
    }
    assert_eq!(hull_faces, 12, "six square faces of two triangles each");
}

#[test]
fn errors() {
    let plane: Vec<[f64; 3]> = (0..30).map(|i| [(i % 5) as f64, (i / 5) as f64, 1.0]).collect();
    assert_eq!(dbrg::tetrahedralize(&plane, &Params::default()).unwrap_err().status, dbrg::Status::DegenerateInput);
    let mut points = cube_points();
    points[3][0] = f64::NAN;
    let error = dbrg::tetrahedralize(&points, &Params::default()).unwrap_err();
    assert_eq!(error.status, dbrg::Status::NonFiniteInput);
    assert!(error.message.contains('3'));
}
