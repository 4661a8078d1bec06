//! Progress closures: stages in order, cancelling with false, panics carried across the C call.

mod common;

use common::fibonacci_sphere;
use dbrg::{Params, Stage, Status};
use std::panic::{self, AssertUnwindSafe};

const ORDER: [Stage; 7] =
    [Stage::Validate, Stage::Clean, Stage::Sort, Stage::Delaunay, Stage::Grow, Stage::FillHoles, Stage::Output];

#[test]
fn stages_arrive_in_pipeline_order() {
    let mut reports = Vec::new();
    let mesh = dbrg::reconstruct_with_progress(&fibonacci_sphere(500), &Params::default(), |stage, fraction| {
        reports.push((stage, fraction));
        true
    })
    .unwrap();
    assert_eq!(mesh.triangles().len(), 996);
    let positions: Vec<usize> = reports.iter().map(|(stage, _)| ORDER.iter().position(|s| s == stage).unwrap()).collect();
    assert!(positions.windows(2).all(|w| w[0] <= w[1]), "{:?}", reports);
    assert!(reports.iter().all(|&(_, f)| (0.0..=1.0).contains(&f)));
    assert!(reports.iter().any(|&(s, _)| s == Stage::Delaunay));
    assert_eq!(reports.last(), Some(&(Stage::Output, 1.0)));
}

#[test]
fn returning_false_cancels() {
    let mut after_cancel = 0;
    let mut cancelled = false;
    let error = dbrg::reconstruct_with_progress(&fibonacci_sphere(500), &Params::default(), |stage, _| {
        if cancelled {
            after_cancel += 1;
        }
        cancelled = cancelled || stage == Stage::Delaunay;
        !cancelled
    })
    .unwrap_err();
    assert_eq!(error.status, Status::Cancelled);
    assert_eq!(after_cancel, 0, "no report after the cancel");
}

#[derive(Debug, PartialEq)]
struct Marker(u32);

#[test]
fn a_panic_in_the_closure_is_resumed_after_the_call() {
    let mut calls_after_panic = 0;
    let mut panicked = false;
    let caught = panic::catch_unwind(AssertUnwindSafe(|| {
        dbrg::reconstruct_with_progress(&fibonacci_sphere(500), &Params::default(), |stage, _| {
            if panicked {
                calls_after_panic += 1;
            }
            if stage == Stage::Delaunay {
                panicked = true;
                panic::panic_any(Marker(7));
            }
            true
        })
    }));
    let payload = caught.expect_err("the panic should come out of reconstruct_with_progress");
    assert_eq!(payload.downcast_ref::<Marker>(), Some(&Marker(7)));
    assert_eq!(calls_after_panic, 0, "the closure is not called again after it panicked");
    // The library is still usable.
    assert!(dbrg::reconstruct(&fibonacci_sphere(100), &Params::default()).is_ok());
}

#[test]
fn tetrahedralize_reports_cancels_and_resumes_panics() {
    let points = fibonacci_sphere(300);
    let mut stages = Vec::new();
    dbrg::tetrahedralize_with_progress(&points, &Params::default(), |stage, _| {
        stages.push(stage);
        true
    })
    .unwrap();
    assert!(stages.contains(&Stage::Delaunay));
    let error = dbrg::tetrahedralize_with_progress(&points, &Params::default(), |stage, _| stage != Stage::Delaunay).unwrap_err();
    assert_eq!(error.status, Status::Cancelled);
    let caught = panic::catch_unwind(|| {
        dbrg::tetrahedralize_with_progress(&fibonacci_sphere(300), &Params::default(), |_, _| -> bool { panic!("stop") })
    });
    assert_eq!(caught.unwrap_err().downcast_ref::<&str>(), Some(&"stop"));
}
