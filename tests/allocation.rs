//! The hot paths allocate nothing: a counting global allocator around
//! residual + Jacobian evaluations of every mapping, flows, vector fields and
//! stick forces.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

use stickslip::models::paper::{Paper, Params};
use stickslip::Model;

struct Counting;

// Per thread, so that tests running in parallel do not count each other.
thread_local! {
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

fn count() {
    let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
}

fn allocations() -> usize {
    ALLOCATIONS.with(Cell::get)
}

// SAFETY-free: delegates to the system allocator and only counts.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn residuals_jacobians_and_flows_allocate_nothing() {
    let p = Params {
        W: 3.7,
        ..Params::default()
    };
    let n_mappings = Paper::INFO.mappings.len();
    let n_domains = Paper::INFO.domains.len();
    let before = allocations();
    let mut sink = 0.0;
    for k in 0..100 {
        let phi1 = 5.0 + 0.01 * k as f64;
        for idx in 0..n_mappings {
            let e = Paper::mapping(&p, idx, 0.3, 4.9, 0.8, phi1);
            sink += e.residual[0] + e.d_prev[(1, 1)] + e.d_next[(0, 1)];
            sink += Paper::residual(&p, idx, 0.3, 4.9, 0.8, phi1)[1];
            sink += e.local_jacobian().map_or(0.0, |m| m[(0, 0)]);
        }
        for j in 0..n_domains {
            sink += Paper::flow(&p, j, 0.3, 2.0, 4.9, phi1)[0];
            sink += Paper::normal_field(&p, j, 0.3, 2.0, phi1)[1];
            sink += Paper::coefficients(&p, j).b;
        }
        sink += Paper::stick_forces(&p, 0.3, phi1).map_or(0.0, |f| f.input_above);
    }
    let after = allocations();
    assert!(sink.is_finite());
    assert_eq!(
        after - before,
        0,
        "{} allocations in the hot path",
        after - before
    );
}

#[test]
fn the_counter_counts() {
    // The check above can fail: an allocation is seen.
    let before = allocations();
    let v: Vec<f64> = std::hint::black_box(vec![1.0; 16]);
    assert!(allocations() > before);
    drop(v);
}
