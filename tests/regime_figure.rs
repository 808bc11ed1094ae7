//! Exact regime maps from synthetic curve sets: the raster's walls never
//! leak, every region's sample lies deep inside its component, regions on
//! the paper's model carry the labels a map gives at their samples, and the
//! figures (regime map, map with curves) are written with every label in
//! full and every codimension-two point marked.

use std::fs;
use std::path::{Path, PathBuf};

use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

use stickslip::bifurcation::TransitionKind;
use stickslip::models::paper::{Paper, Params};
use stickslip::output::figure::layout::Rect;
use stickslip::output::figure::map::{draw_map_with_curves, MapFigure};
use stickslip::output::figure::regime::{curve_style, plot_regimes, RegimeFigure};
use stickslip::output::figure::register;
use stickslip::study::curves::regions::{classify_partition, min_cells, partition, Partition};
use stickslip::study::curves::{regions, Codim2Point, CurveSet, CurveSummary};
use stickslip::study::map::{classify_point, GridAxis, MapFile};

fn dir() -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join("regime_figure");
    fs::create_dir_all(&d).unwrap();
    d
}

fn curve(kind: TransitionKind, points: Vec<[f64; 2]>) -> CurveSummary {
    CurveSummary {
        kind,
        boundary: None,
        structure: "P_{3_33 4_33}".to_string(),
        from: None,
        to: None,
        points,
        at: Vec::new(),
    }
}

fn set(x: [f64; 2], y: [f64; 2], curves: Vec<CurveSummary>) -> CurveSet {
    CurveSet {
        x: ("W".to_string(), x),
        y: ("Q0".to_string(), y),
        curves,
        codim2: Vec::new(),
        failed_starts: Vec::new(),
    }
}

/// A closed polygon around `c` of radius `r(θ)`, `n` corners (first = last).
fn closed(c: [f64; 2], n: usize, r: impl Fn(f64) -> [f64; 2]) -> Vec<[f64; 2]> {
    (0..=n)
        .map(|k| {
            let t = std::f64::consts::TAU * (k % n) as f64 / n as f64;
            let [rx, ry] = r(t);
            [c[0] + rx * t.cos(), c[1] + ry * t.sin()]
        })
        .collect()
}

/// Whether `p` lies inside the closed polygon `poly` (even–odd rule).
fn inside(poly: &[[f64; 2]], p: [f64; 2]) -> bool {
    let mut odd = false;
    for w in poly.windows(2) {
        let ([x0, y0], [x1, y1]) = (w[0], w[1]);
        if (y0 > p[1]) != (y1 > p[1]) {
            let x = x0 + (p[1] - y0) / (y1 - y0) * (x1 - x0);
            if p[0] < x {
                odd = !odd;
            }
        }
    }
    odd
}

/// Distance from `p` to the polyline `poly`.
fn distance(poly: &[[f64; 2]], p: [f64; 2]) -> f64 {
    poly.windows(2)
        .map(|w| {
            let (a, b) = (w[0], w[1]);
            let d = [b[0] - a[0], b[1] - a[1]];
            let l2 = d[0] * d[0] + d[1] * d[1];
            let t = if l2 > 0.0 {
                (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / l2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (p[0] - a[0] - t * d[0]).hypot(p[1] - a[1] - t * d[1])
        })
        .fold(f64::INFINITY, f64::min)
}

/// The cell units of a box `[0, nx] × [0, ny]` from `[x, y]`.
fn units(cut: &Partition, p: [f64; 2]) -> [f64; 2] {
    let r = &cut.raster;
    [
        (p[0] - r.x[0]) / (r.x[1] - r.x[0]) * r.nx as f64,
        (p[1] - r.y[0]) / (r.y[1] - r.y[0]) * r.ny as f64,
    ]
}

/// Every free cell whose centre is inside the closed polygon `poly` lies
/// in another component than every free cell outside. Returns the number
/// of free cells inside and outside.
fn assert_separates(cut: &Partition, poly: &[[f64; 2]]) -> (usize, usize) {
    let poly_u: Vec<[f64; 2]> = poly.iter().map(|&p| units(cut, p)).collect();
    let (mut ins, mut outs) = (Vec::new(), Vec::new());
    for (i, c) in cut.component.iter().enumerate() {
        let Some(k) = *c else { continue };
        let p = units(cut, cut.raster.centre(i));
        if inside(&poly_u, p) {
            ins.push(k);
        } else {
            outs.push(k);
        }
    }
    for k in &ins {
        assert!(!outs.contains(k), "component {k} leaks across the curve");
    }
    (ins.len(), outs.len())
}

#[test]
fn closed_curves_never_leak() {
    let mut rng = StdRng::seed_from_u64(12);
    for case in 0..60 {
        let (nx, ny) = (rng.gen_range(8..60), rng.gen_range(8..60));
        let c = [rng.gen_range(3.0..7.0), rng.gen_range(30.0..70.0)];
        let corners = rng.gen_range(3..40);
        let radii: Vec<f64> = (0..corners).map(|_| rng.gen_range(0.3..1.0)).collect();
        let poly = closed(c, corners, |t| {
            let k = ((t / std::f64::consts::TAU) * corners as f64).round() as usize % corners;
            [2.8 * radii[k], 28.0 * radii[k]]
        });
        let s = set(
            [0.0, 10.0],
            [0.0, 100.0],
            vec![curve(TransitionKind::Grazing, poly.clone())],
        );
        let cut = partition(&s, nx, ny);
        assert_separates(&cut, &poly);
        // The wall is no thicker than a traversal: every wall cell is within
        // a cell's diagonal of the curve.
        let poly_u: Vec<[f64; 2]> = poly.iter().map(|&p| units(&cut, p)).collect();
        for (i, &w) in cut.wall.iter().enumerate() {
            if w {
                let d = distance(&poly_u, units(&cut, cut.raster.centre(i)));
                assert!(
                    d <= 0.5f64.hypot(0.5) + 1e-9,
                    "case {case}: wall cell {i} at {d}"
                );
            }
        }
    }
}

#[test]
fn a_closed_curve_gives_an_inside_and_an_outside() {
    // A circle of 9 cells' radius (cells are 0.25 × 10/3).
    let poly = closed([5.0, 50.0], 64, |_| [9.0 * 0.25, 9.0 * 10.0 / 3.0]);
    let s = set(
        [0.0, 10.0],
        [0.0, 100.0],
        vec![curve(TransitionKind::StickOnset, poly.clone())],
    );
    let cut = partition(&s, 40, 30);
    assert_eq!(cut.components.len(), 2, "{:?}", cut.components);
    let (ins, outs) = assert_separates(&cut, &poly);
    assert!(ins > 100 && outs > 500, "{ins} {outs}");
    // The inside's sample is a cell next to the centre (the circle's
    // deepest point), about 8.5 cells from the wall.
    let inner = cut.component[cut.raster.nx * 15 + 20].expect("centre is free");
    let c = &cut.components[inner];
    let sample = cut.raster.centre(c.sample);
    assert!(
        (sample[0] - 5.0).abs() < 0.25 && (sample[1] - 50.0).abs() < 10.0 / 3.0,
        "{sample:?}"
    );
    assert!((7.5..=9.0).contains(&c.depth), "{}", c.depth);
}

#[test]
fn diagonals_through_cell_corners_split_the_box_in_two() {
    // Corner to corner of square cells: the line passes through every
    // cell vertex on its way, the case where a thin line leaks 4-connected.
    for (nx, ny) in [(20, 20), (30, 10), (7, 21)] {
        for line in [
            vec![[0.0, 0.0], [10.0, 100.0]],
            vec![[0.0, 100.0], [10.0, 0.0]],
        ] {
            let s = set(
                [0.0, 10.0],
                [0.0, 100.0],
                vec![curve(TransitionKind::Fold, line.clone())],
            );
            let cut = partition(&s, nx, ny);
            assert_eq!(cut.components.len(), 2, "{nx}×{ny} {line:?}");
            // Close the line around one side to tell the sides apart.
            let mut poly = line.clone();
            poly.push([line[1][0], line[0][1]]);
            poly.push(line[0]);
            let (a, b) = assert_separates(&cut, &poly);
            assert!(a > 0 && b > 0);
        }
    }
}

#[test]
fn a_curve_ending_inside_the_box_separates_nothing() {
    let mut s = set(
        [0.0, 10.0],
        [0.0, 100.0],
        vec![curve(
            TransitionKind::Grazing,
            vec![[0.0, 50.0], [6.0, 50.0]],
        )],
    );
    s.codim2.push(Codim2Point {
        x: 6.0,
        y: 50.0,
        kinds: vec![TransitionKind::Grazing, TransitionKind::StickOnset],
        curves: vec![0],
    });
    let cut = partition(&s, 40, 40);
    assert_eq!(cut.components.len(), 1);
    assert!(cut.wall.iter().filter(|&&w| w).count() >= 24);
}

/// The squared distance from cell `i` to the nearest wall or the outside,
/// by brute force.
fn brute_depth2(cut: &Partition, i: usize) -> i64 {
    let (nx, ny) = (cut.raster.nx as i64, cut.raster.ny as i64);
    let (x, y) = (i as i64 % nx, i as i64 / nx);
    let edge = [x + 1, nx - x, y + 1, ny - y]
        .into_iter()
        .map(|d| d * d)
        .min()
        .unwrap();
    (0..cut.wall.len())
        .filter(|&j| cut.wall[j])
        .map(|j| {
            let (a, b) = (j as i64 % nx - x, j as i64 / nx - y);
            a * a + b * b
        })
        .fold(edge, i64::min)
}

#[test]
fn samples_are_the_deepest_cells_of_their_components() {
    let mut rng = StdRng::seed_from_u64(7);
    for _ in 0..8 {
        let lines: Vec<CurveSummary> = (0..4)
            .map(|_| {
                let pts = (0..5)
                    .map(|_| [rng.gen_range(-1.0..11.0), rng.gen_range(-10.0..110.0)])
                    .collect();
                curve(TransitionKind::PeriodDoubling, pts)
            })
            .collect();
        let s = set([0.0, 10.0], [0.0, 100.0], lines);
        let cut = partition(&s, 36, 27);
        let depth: Vec<i64> = (0..cut.wall.len()).map(|i| brute_depth2(&cut, i)).collect();
        for (k, c) in cut.components.iter().enumerate() {
            assert_eq!(cut.component[c.sample], Some(k), "sample in its component");
            assert!(!cut.wall[c.sample]);
            let cells: Vec<usize> = (0..cut.wall.len())
                .filter(|&i| cut.component[i] == Some(k))
                .collect();
            assert_eq!(cells.len(), c.cells);
            let deepest = cells.iter().map(|&i| depth[i]).max().unwrap();
            assert_eq!(depth[c.sample], deepest, "component {k}");
            assert!((c.depth - (deepest as f64).sqrt()).abs() < 1e-12);
            assert!(
                c.depth >= 1.0,
                "a sample is never next to a wall or the edge"
            );
        }
    }
}

/// Five regions: two crossing lines and a closed curve in one quadrant.
fn synthetic_set(x: [f64; 2], y: [f64; 2]) -> CurveSet {
    let at = |u: f64, v: f64| [x[0] + u * (x[1] - x[0]), y[0] + v * (y[1] - y[0])];
    let mut s = set(
        x,
        y,
        vec![
            curve(
                TransitionKind::Grazing,
                vec![at(-0.1, 0.55), at(0.45, 0.5), at(1.1, 0.6)],
            ),
            curve(
                TransitionKind::StickOnset,
                vec![at(0.4, -0.1), at(0.45, 0.5), at(0.55, 1.1)],
            ),
            curve(
                TransitionKind::NeimarkSacker,
                closed(at(0.78, 0.22), 40, |_| {
                    [0.12 * (x[1] - x[0]), 0.12 * (y[1] - y[0])]
                }),
            ),
            // A curve that ends at a codimension-two point inside the box.
            curve(
                TransitionKind::PeriodDoubling,
                vec![at(0.0, 0.85), at(0.2, 0.8)],
            ),
        ],
    );
    let [cx, cy] = at(0.2, 0.8);
    s.codim2.push(Codim2Point {
        x: cx,
        y: cy,
        kinds: vec![TransitionKind::PeriodDoubling, TransitionKind::Grazing],
        curves: vec![3],
    });
    let [cx, cy] = at(0.45, 0.5);
    s.codim2.push(Codim2Point {
        x: cx,
        y: cy,
        kinds: vec![TransitionKind::Grazing, TransitionKind::StickOnset],
        curves: vec![0, 1],
    });
    s
}

#[test]
fn regions_of_the_paper_model_carry_the_labels_of_a_map_at_their_samples() {
    let base = Params::default();
    let s = synthetic_set([0.2, 8.0], [0.0, 180.0]);
    let (nx, ny) = (40, 30);
    let r = regions::<Paper>(&base, &s, nx, ny);
    let cut = partition(&s, nx, ny);
    assert_eq!((r.nx, r.ny, r.cells.len()), (nx, ny, nx * ny));
    // One region per component large enough: four quadrants and the inside
    // of the closed curve.
    let big: Vec<usize> = (0..cut.components.len())
        .filter(|&k| cut.components[k].cells >= min_cells(nx, ny))
        .collect();
    assert_eq!(big.len(), 5);
    assert_eq!(r.regions.len(), big.len());
    for (region, &k) in r.regions.iter().zip(&big) {
        let i = cut.components[k].sample;
        assert_eq!(region.sample, cut.raster.centre(i));
        let axis = |name: &str, v: f64| GridAxis {
            name: name.into(),
            from: v,
            to: v,
            count: 1,
        };
        let p = classify_point::<Paper>(
            &base,
            &axis("W", region.sample[0]),
            &axis("Q0", region.sample[1]),
            0,
        );
        assert_eq!(region.label, p.label(), "at {:?}", region.sample);
        assert!(!region.label.is_empty());
    }
    // Every free cell of a classified component has its component's region.
    for (i, c) in cut.component.iter().enumerate() {
        if let Some(pos) = c.and_then(|c| big.iter().position(|&k| k == c)) {
            assert_eq!(r.cells[i], pos, "cell {i}");
        }
    }
}

/// Which side of each curve of [`synthetic_set`] on the unit box `p` lies:
/// above the grazing line, right of the stick-onset line, inside the circle.
fn side(s: &CurveSet, p: [f64; 2]) -> String {
    let along = |poly: &[[f64; 2]], i: usize, t: f64| {
        let w = poly
            .windows(2)
            .find(|w| (w[0][i].min(w[1][i])..=w[0][i].max(w[1][i])).contains(&t))
            .unwrap();
        let f = (t - w[0][i]) / (w[1][i] - w[0][i]);
        w[0][1 - i] + f * (w[1][1 - i] - w[0][1 - i])
    };
    let above = p[1] > along(&s.curves[0].points, 0, p[0]);
    let right = p[0] > along(&s.curves[1].points, 1, p[1]);
    let within = inside(&s.curves[2].points, p);
    format!("{above}{right}{within}")
}

#[test]
fn walls_and_tiny_components_take_the_region_on_their_side() {
    let s = synthetic_set([0.0, 1.0], [0.0, 1.0]);
    for (nx, ny) in [(60, 40), (37, 53), (200, 150)] {
        let cut = partition(&s, nx, ny);
        let a = classify_partition(&cut, |p| side(&s, p));
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        let serial = one.install(|| classify_partition(&cut, |p| side(&s, p)));
        assert_eq!(a, serial, "the same on one thread");
        assert_eq!(a.regions.len(), 5);
        // Every cell, wall or not, is coloured by the side its centre lies
        // on; only cells right by the crossing may be shut in between the
        // curves and take a neighbour's region.
        let mut wrong = 0;
        for i in 0..cut.wall.len() {
            let c = cut.raster.centre(i);
            if a.regions[a.cells[i]].label != side(&s, c) {
                let near = (c[0] - 0.45).hypot(c[1] - 0.5) < 2.0 / nx.min(ny) as f64;
                assert!(near, "{nx}×{ny}: cell {i} at {c:?}");
                wrong += 1;
            }
        }
        assert!(wrong <= 2, "{wrong}");
        assert!(cut.wall.iter().filter(|&&w| w).count() > nx + ny);
    }
}

fn svg_text(path: &Path) -> String {
    let svg = fs::read_to_string(path).unwrap();
    svg.split("<text")
        .skip(1)
        .filter_map(|t| t.split_once('>').and_then(|(_, r)| r.split_once("</text>")))
        .map(|(t, _)| t.to_string())
        .collect::<Vec<_>>()
        .join(" ")
}

fn squeeze(s: &str) -> String {
    s.split_whitespace().collect()
}

fn assert_apart(boxes: &[Rect]) {
    let drawn: Vec<&Rect> = boxes.iter().filter(|r| r.x1 > r.x0).collect();
    for (i, a) in drawn.iter().enumerate() {
        for b in &drawn[i + 1..] {
            assert!(!a.overlaps(b), "{a:?} overlaps {b:?}");
        }
    }
}

/// The centres of the dark filled polygons of an SVG (the diamonds).
fn marks(path: &Path) -> Vec<(f64, f64)> {
    let svg = fs::read_to_string(path).unwrap();
    svg.split("<polygon")
        .skip(1)
        .filter(|p| p.contains("fill=\"#141414\""))
        .map(|p| {
            let pts = p
                .split("points=\"")
                .nth(1)
                .unwrap()
                .split('"')
                .next()
                .unwrap();
            let xy: Vec<(f64, f64)> = pts
                .split_whitespace()
                .map(|q| {
                    let (a, b) = q.split_once(',').unwrap();
                    (a.parse().unwrap(), b.parse().unwrap())
                })
                .collect();
            let n = xy.len() as f64;
            (
                xy.iter().map(|p| p.0).sum::<f64>() / n,
                xy.iter().map(|p| p.1).sum::<f64>() / n,
            )
        })
        .collect()
}

#[test]
fn the_regime_figure_names_every_region_in_full_and_marks_codim2_points() {
    register().unwrap();
    let s = synthetic_set([0.2, 8.0], [0.0, 180.0]);
    let cut = partition(&s, 80, 60);
    let long =
        "P_{3_31 0_11 3_13 4_33 3_31 0_11 3_13 4_33 3_33 4_33 3_33 4_33 3_33 4_33 3_33 4_33}^6";
    // A long name, two coexisting motions, NM: the legend must show them whole.
    let name = |[w, q]: [f64; 2]| -> String {
        match (w > 4.0, q > 90.0) {
            (false, false) => long.to_string(),
            (true, false) if (w - 6.3).hypot((q - 40.0) / 18.0) < 1.0 => "NM".to_string(),
            (true, false) => format!("NM + {long}"),
            (false, true) => "P_{3_33 4_33}".to_string(),
            (true, true) => "P_{3_31 0_11 3_13 4_33}".to_string(),
        }
    };
    let r = classify_partition(&cut, name);
    assert_eq!(r.regions.len(), 5);
    let figure = RegimeFigure::new(&s, &r, "regimes").unwrap();
    let (boxes, frame) = figure.legend_boxes();
    for b in &boxes {
        assert!(b.inside(&frame), "{b:?} leaves {frame:?}");
    }
    assert_apart(&boxes);
    let svg = dir().join("regimes.svg");
    let png = dir().join("regimes.png");
    plot_regimes(&s, &r, "regimes", &svg).unwrap();
    plot_regimes(&s, &r, "regimes", &png).unwrap();
    assert!(fs::metadata(&png).unwrap().len() > 10_000);
    let text = squeeze(&svg_text(&svg));
    for region in &r.regions {
        assert!(
            text.contains(&squeeze(&region.label)),
            "`{}` not in full",
            region.label
        );
    }
    for (k, region) in r.regions.iter().enumerate() {
        let entry = format!("{}: {}", k + 1, region.label);
        let numbered = (0..r.regions.len())
            .filter(|&j| r.regions[j].label == region.label)
            .count()
            > 1;
        assert!(numbered || text.contains(&squeeze(&entry)), "`{entry}`");
    }
    for kind in [
        "grazing",
        "stick onset",
        "neimark sacker",
        "period doubling",
    ] {
        assert!(text.contains(&squeeze(kind)), "kind `{kind}` in the legend");
    }
    assert!(text.contains(&squeeze("grazing × stick onset (1)")));
    // Two codimension-two points in the plot, a diamond for each of their
    // (two) combinations of kinds in the legend.
    assert!(text.contains(&squeeze("grazing × period doubling (1)")));
    let m = marks(&svg);
    assert_eq!(m.len(), 4, "{m:?}");
    let legend_x = f64::from(boxes[0].x0) - 20.0;
    assert_eq!(m.iter().filter(|p| p.0 < legend_x).count(), 2);
    // The curves in their kinds' inks.
    let raw = fs::read_to_string(&svg).unwrap();
    for kind in [
        TransitionKind::Grazing,
        TransitionKind::StickOnset,
        TransitionKind::NeimarkSacker,
    ] {
        let c = curve_style(kind).0;
        let hex = format!("#{:02X}{:02X}{:02X}", c.0, c.1, c.2);
        assert!(
            raw.contains(&format!("stroke=\"{hex}\"")),
            "{kind:?} drawn in {hex}"
        );
    }
}

#[test]
fn bad_regions_give_an_error() {
    let s = synthetic_set([0.0, 1.0], [0.0, 1.0]);
    let cut = partition(&s, 10, 10);
    let mut r = classify_partition(&cut, |_| "NM".to_string());
    r.cells.pop();
    assert!(RegimeFigure::new(&s, &r, "x").is_err());
    r.cells.push(99);
    assert!(RegimeFigure::new(&s, &r, "x").is_err());
    r.cells.pop();
    r.cells.push(0);
    assert!(RegimeFigure::new(&s, &r, "x").is_ok());
    let mut flat = s.clone();
    flat.y.1 = [2.0, 2.0];
    let e = RegimeFigure::new(&flat, &r, "x").err().unwrap();
    assert!(e.contains("Q0"), "{e}");
    // A degenerate box or a raster of no cells: no panic, one region.
    let cut = partition(&flat, 0, 5);
    assert_eq!(
        (cut.raster.nx, cut.wall.iter().filter(|&&w| w).count()),
        (1, 0)
    );
    assert_eq!(
        classify_partition(&cut, |_| "NM".to_string()).regions.len(),
        1
    );
}

#[test]
fn a_point_that_is_not_finite_breaks_a_curve() {
    // Two pieces of a horizontal line with a gap where a NaN point sits:
    // nothing bridges the gap, so the box stays one component.
    let line = vec![
        [0.0, 50.0],
        [4.0, 50.0],
        [f64::NAN, 50.0],
        [6.0, 50.0],
        [10.0, 50.0],
    ];
    let s = set(
        [0.0, 10.0],
        [0.0, 100.0],
        vec![curve(TransitionKind::Grazing, line)],
    );
    let cut = partition(&s, 20, 20);
    assert_eq!(cut.components.len(), 1);
    let whole = set(
        [0.0, 10.0],
        [0.0, 100.0],
        vec![curve(
            TransitionKind::Grazing,
            vec![[0.0, 50.0], [10.0, 50.0]],
        )],
    );
    assert_eq!(partition(&whole, 20, 20).components.len(), 2);
}

fn map_file(name: &str, nx: usize, ny: usize) -> PathBuf {
    let path = dir().join(name);
    let mut text = format!(
        "# stickslip map model=paper x=W=0.2:8:{nx} y=Q0=0:180:{ny} base=m=5,d=0.1,c=30,V=3,V1=4.5,V2=1.5,mus=0.5,muk=0.4,mu1=0.1,mu2=0.5,mu3=0.1,mu4=0.5,g=9.8\nindex,W,Q0,status,motions\n"
    );
    for i in 0..nx * ny {
        let (w, q) = (
            0.2 + 7.8 * (i % nx) as f64 / (nx - 1) as f64,
            180.0 * (i / nx) as f64 / (ny - 1) as f64,
        );
        let m = if q > 90.0 { "P_{3_33 4_33}" } else { "NM" };
        text.push_str(&format!("{i},{w},{q},\"ok\",\"{m}\"\n"));
    }
    fs::write(&path, text).unwrap();
    path
}

#[test]
fn a_map_with_curves_is_drawn() {
    register().unwrap();
    let map = MapFile::read(&map_file("map.csv", 12, 9)).unwrap();
    let s = synthetic_set([0.2, 8.0], [0.0, 180.0]);
    for ext in ["svg", "png"] {
        let out = dir().join(format!("map_curves.{ext}"));
        draw_map_with_curves(&map, Some(&s), &out).unwrap();
        assert!(fs::metadata(&out).unwrap().len() > 1000);
    }
    let svg = dir().join("map_curves.svg");
    let text = squeeze(&svg_text(&svg));
    assert!(text.contains("stickonset") && text.contains("neimarksacker"));
    assert_eq!(
        marks(&svg).len(),
        4,
        "two codim-2 points and the legend's two diamonds"
    );
    let with = MapFigure::with_curves(&map, &s).unwrap();
    let (boxes, frame) = with.legend_boxes();
    assert!(boxes.iter().all(|b| b.inside(&frame)));
    assert_apart(&boxes);
    assert!(boxes.len() > MapFigure::new(&map).legend_boxes().0.len());
    // Axes swapped: drawn the right way round; other parameters: an error.
    let mut swapped = s.clone();
    std::mem::swap(&mut swapped.x, &mut swapped.y);
    for c in &mut swapped.curves {
        for p in &mut c.points {
            p.swap(0, 1);
        }
    }
    for p in &mut swapped.codim2 {
        std::mem::swap(&mut p.x, &mut p.y);
    }
    let svg2 = dir().join("map_curves_swapped.svg");
    draw_map_with_curves(&map, Some(&swapped), &svg2).unwrap();
    assert_eq!(marks(&svg2), marks(&svg), "the same marks either way");
    let mut other = s.clone();
    other.x.0 = "m".to_string();
    let e = draw_map_with_curves(&map, Some(&other), &dir().join("bad.svg")).unwrap_err();
    assert!(e.to_string().contains("(m, Q0)"), "{e}");
    // Without curves: as before.
    draw_map_with_curves(&map, None, &dir().join("map_plain.svg")).unwrap();
    assert_eq!(marks(&dir().join("map_plain.svg")).len(), 0);
}

/// The cost of a 400 × 300 raster with twelve regions on the paper's model:
/// `cargo test --test regime_figure -- --ignored --nocapture timing`.
#[test]
#[ignore = "a measurement, not a check"]
fn timing_of_a_400_by_300_raster() {
    let (x, y) = ([0.2, 8.0], [0.0, 180.0]);
    let at = |u: f64, v: f64| [x[0] + u * (x[1] - x[0]), y[0] + v * (y[1] - y[0])];
    let mut curves = Vec::new();
    for v in [0.25, 0.5, 0.75] {
        curves.push(curve(
            TransitionKind::Grazing,
            (0..=20)
                .map(|k| {
                    let u = k as f64 / 20.0;
                    at(u, v + 0.05 * (6.0 * u).sin())
                })
                .collect(),
        ));
    }
    for u in [0.3, 0.65] {
        curves.push(curve(
            TransitionKind::Fold,
            (0..=20)
                .map(|k| {
                    let v = k as f64 / 20.0;
                    at(u + 0.04 * (5.0 * v).cos(), v)
                })
                .collect(),
        ));
    }
    let s = set(x, y, curves);
    let t = std::time::Instant::now();
    let cut = partition(&s, 400, 300);
    let raster = t.elapsed();
    let t = std::time::Instant::now();
    let r = regions::<Paper>(&Params::default(), &s, 400, 300);
    let all = t.elapsed();
    let t = std::time::Instant::now();
    let _ = classify_partition(&cut, |p| side(&synthetic_set(x, y), p));
    let cheap = t.elapsed();
    println!(
        "400 × 300, {} components, {} regions: partition {raster:?}, regions (partition + classification) {all:?}, naming the regions with a trivial classifier {cheap:?}, threads {}",
        cut.components.len(),
        r.regions.len(),
        rayon::current_num_threads()
    );
    for (k, g) in r.regions.iter().enumerate() {
        println!("{}: {:?} {}", k + 1, g.sample, g.label);
    }
    for ext in ["png", "svg"] {
        let out = dir().join(format!("timing.{ext}"));
        let t = std::time::Instant::now();
        plot_regimes(&s, &r, "paper: 400 × 300 raster, synthetic curves", &out).unwrap();
        let size = fs::metadata(&out).unwrap().len();
        println!("{ext}: drawn in {:?}, {size} bytes", t.elapsed());
    }
}
