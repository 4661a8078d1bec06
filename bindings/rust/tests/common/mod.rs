//! Point sets the tests generate, and checks of a triangle mesh that do not trust the library.
#![allow(dead_code)]

use std::collections::{HashMap, HashSet};

/// `count` points spread evenly over the unit sphere (the golden-angle spiral).
pub fn fibonacci_sphere(count: usize) -> Vec<[f64; 3]> {
    let golden_angle = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..count)
        .map(|i| {
            let z = 1.0 - (2 * i + 1) as f64 / count as f64;
            let r = (1.0 - z * z).sqrt();
            let a = golden_angle * i as f64;
            [r * a.cos(), r * a.sin(), z]
        })
        .collect()
}

/// A jittered side x side grid on z = 0.2 (x^2 + y^2): an open surface with one border.
pub fn paraboloid_patch(side: usize) -> Vec<[f64; 3]> {
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    let mut jitter = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let mut points = Vec::new();
    for i in 0..side {
        for j in 0..side {
            let x = -1.0 + 2.0 * i as f64 / (side - 1) as f64 + 0.3 * jitter() / side as f64;
            let y = -1.0 + 2.0 * j as f64 / (side - 1) as f64 + 0.3 * jitter() / side as f64;
            points.push([x, y, 0.2 * (x * x + y * y)]);
        }
    }
    points
}

fn directed_edges(triangles: &[[u32; 3]]) -> Vec<(u32, u32)> {
    triangles.iter().flat_map(|&[a, b, c]| vec![(a, b), (b, c), (c, a)]).collect()
}

/// Every way `triangles` fails to be an oriented manifold (empty when it is one): degenerate or
/// duplicate faces, an edge with more than two faces (or one, unless allowed), two faces traversing an
/// edge the same way, a vertex whose faces form more than one fan.
pub fn manifold_problems(triangles: &[[u32; 3]], allow_boundary: bool) -> Vec<String> {
    let mut problems = Vec::new();
    let mut faces = HashSet::new();
    for t in triangles {
        if t[0] == t[1] || t[1] == t[2] || t[2] == t[0] {
            problems.push(format!("degenerate triangle {:?}", t));
        }
        let mut key = *t;
        key.sort_unstable();
        if !faces.insert(key) {
            problems.push(format!("duplicate triangle {:?}", t));
        }
    }
    let mut directed: HashMap<(u32, u32), u32> = HashMap::new();
    let mut undirected: HashMap<(u32, u32), u32> = HashMap::new();
    for (a, b) in directed_edges(triangles) {
        *directed.entry((a, b)).or_insert(0) += 1;
        *undirected.entry((a.min(b), a.max(b))).or_insert(0) += 1;
    }
    for (edge, count) in &directed {
        if *count > 1 {
            problems.push(format!("directed edge {:?} appears {} times", edge, count));
        }
    }
    for (edge, count) in &undirected {
        if *count > 2 || (*count == 1 && !allow_boundary) {
            problems.push(format!("edge {:?} has {} triangles", edge, count));
        }
    }
    // Around each vertex v, the opposite edges p -> q of its faces (v, p, q) must chain into one fan.
    let mut link: HashMap<u32, HashMap<u32, u32>> = HashMap::new();
    for &[a, b, c] in triangles {
        for (v, p, q) in [(a, b, c), (b, c, a), (c, a, b)] {
            link.entry(v).or_default().insert(p, q);
        }
    }
    for (v, step) in &link {
        let targets: HashSet<u32> = step.values().copied().collect();
        let starts: Vec<u32> = step.keys().copied().filter(|p| !targets.contains(p)).collect();
        if starts.len() > 1 {
            problems.push(format!("vertex {} has {} fans", v, starts.len()));
            continue;
        }
        let start = starts.first().copied().unwrap_or_else(|| *step.keys().next().unwrap());
        let (mut p, mut seen) = (start, 0);
        while let Some(&q) = step.get(&p) {
            p = q;
            seen += 1;
            if p == start || seen > step.len() {
                break;
            }
        }
        if seen != step.len() {
            problems.push(format!("the faces around vertex {} form more than one fan", v));
        }
    }
    problems
}

/// V - E + F over the vertices the triangles use.
pub fn euler_characteristic(triangles: &[[u32; 3]]) -> i64 {
    let vertices: HashSet<u32> = triangles.iter().flatten().copied().collect();
    let edges: HashSet<(u32, u32)> = directed_edges(triangles).into_iter().map(|(a, b)| (a.min(b), a.max(b))).collect();
    vertices.len() as i64 - edges.len() as i64 + triangles.len() as i64
}

/// Six times the signed volume enclosed by the triangles: positive when a closed surface faces outward.
pub fn signed_volume6(points: &[[f64; 3]], triangles: &[[u32; 3]]) -> f64 {
    triangles
        .iter()
        .map(|t| {
            let [a, b, c] = [points[t[0] as usize], points[t[1] as usize], points[t[2] as usize]];
            let cross = [b[1] * c[2] - b[2] * c[1], b[2] * c[0] - b[0] * c[2], b[0] * c[1] - b[1] * c[0]];
            a[0] * cross[0] + a[1] * cross[1] + a[2] * cross[2]
        })
        .sum()
}

/// The oriented triangles, each rotated to start at its smallest index.
pub fn canonical(triangles: &[[u32; 3]]) -> HashSet<[u32; 3]> {
    triangles
        .iter()
        .map(|&[a, b, c]| [[a, b, c], [b, c, a], [c, a, b]].into_iter().min().unwrap())
        .collect()
}
