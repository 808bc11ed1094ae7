//! The figures' layout: tags and legends never overlap and never leave the
//! image — over the real sweep of the paper's model at Q0 = 70 (the README's
//! figure) and a map whose sets have long names, or very many.

use std::fs;
use std::path::{Path, PathBuf};

use stickslip::models::paper::{Paper, Params};
use stickslip::output::figure::layout::Rect;
use stickslip::output::figure::map::MapFigure;
use stickslip::output::figure::sweep::{tags, SweepFigure};
use stickslip::output::figure::{register, Figure};
use stickslip::study::map::MapFile;
use stickslip::study::sweep::{sweep, SweepOptions};

fn image(f: &impl Figure) -> Rect {
    let (w, h) = f.size();
    Rect::at(0, 0, (w as i32, h as i32))
}

fn assert_apart(boxes: &[Rect], what: &str) {
    for (i, a) in boxes.iter().enumerate() {
        for b in &boxes[i + 1..] {
            assert!(!a.overlaps(b), "{what}: {a:?} overlaps {b:?}");
        }
    }
}

/// The numbers `a..=b` of a tag's text (`7`, `7,8`, `7–12`).
fn numbers(text: &str) -> Vec<usize> {
    let n = |s: &str| s.parse::<usize>().expect("a number");
    if let Some((a, b)) = text.split_once('–') {
        (n(a)..=n(b)).collect()
    } else {
        text.split(',').map(n).collect()
    }
}

#[test]
fn sweep_tags_and_key_of_the_readme_figure_are_apart_and_inside() {
    register().unwrap();
    let base = Params {
        Q0: 70.0,
        ..Params::default()
    };
    let s = sweep::<Paper>(base, "W", 0.2, 9.0, 200, SweepOptions::default()).expect("sweep runs");
    assert!(
        s.transitions.len() >= 20,
        "{} transitions",
        s.transitions.len()
    );
    let figure = SweepFigure::new(&s, "sweep");
    let frame = image(&figure);
    let (panels, key) = figure.placed().unwrap();
    assert_eq!(panels.len(), 2, "tags over both upper panels");
    let mut values: Vec<f64> = s.transitions.iter().map(|t| t.value).collect();
    values.sort_by(f64::total_cmp);
    for tags in &panels {
        let boxes: Vec<Rect> = tags.iter().map(|t| t.rect).collect();
        assert_apart(&boxes, "tags");
        // Every transition is named by exactly one tag, in order.
        let named: Vec<usize> = tags.iter().flat_map(|t| numbers(&t.text)).collect();
        assert_eq!(named, (1..=values.len()).collect::<Vec<_>>());
        for t in tags {
            assert!(t.rect.inside(&frame), "{t:?} leaves the image");
            assert_eq!(numbers(&t.text).first(), Some(&t.numbers.0));
            // Over its line unless pushed in from the image's edge.
            let centre = (t.rect.x0 + t.rect.x1) / 2;
            assert!(
                (centre - t.line).abs() <= 1 || t.rect.x1 >= frame.x1 - 16,
                "{t:?}"
            );
        }
        // Lines share a tag only when within a couple of pixels, and the
        // crowded stretches do need rows.
        assert!(tags.len() >= 8, "{} tags", tags.len());
        assert!(
            tags.iter().any(|t| t.rect.y0 < tags[0].rect.y0),
            "no stacking"
        );
    }
    // Tags of the two panels do not meet either.
    let all: Vec<Rect> = panels.iter().flatten().map(|t| t.rect).collect();
    assert_apart(&all, "tags of both panels");
    // The key: every box inside the image, none overlapping another or a tag.
    for r in &key {
        assert!(r.inside(&frame), "{r:?} leaves the image {frame:?}");
    }
    let mut boxes = key.clone();
    boxes.retain(|r| r.x1 > r.x0);
    boxes.extend(all);
    assert_apart(&boxes, "key and tags");
}

#[test]
fn tags_of_lines_at_one_pixel_share_a_tag_and_rows_keep_apart() {
    register().unwrap();
    // Six lines within a pixel, two pairs, and lines at both edges.
    let lines = [0, 40, 41, 41, 41, 42, 42, 90, 91, 200, 203, 599, 600];
    let tags = tags(&lines, 0, 600);
    let texts: Vec<&str> = tags.iter().map(|t| t.text.as_str()).collect();
    assert_eq!(texts, ["1", "2–7", "8,9", "10", "11", "12,13"]);
    let boxes: Vec<Rect> = tags.iter().map(|t| t.rect).collect();
    assert_apart(&boxes, "tags");
    for r in &boxes {
        assert!(r.x0 >= 0 && r.x1 <= 600 && r.y1 <= 0, "{r:?}");
    }
}

fn map_file(name: &str, nx: usize, ny: usize, motions: impl Fn(usize) -> String) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("figures");
    fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    let step = |n: usize, i: usize| {
        if n > 1 {
            i as f64 / (n - 1) as f64
        } else {
            0.0
        }
    };
    let mut text = format!(
        "# stickslip map model=paper x=W=1:2:{nx} y=Q0=60:70:{ny} base=m=5,d=0.1,c=30,V=3,V1=4.5,V2=1.5,mus=0.5,muk=0.4,mu1=0.1,mu2=0.5,mu3=0.1,mu4=0.5,g=9.8\nindex,W,Q0,status,motions\n"
    );
    for i in 0..nx * ny {
        let (w, q) = (1.0 + step(nx, i % nx), 60.0 + 10.0 * step(ny, i / nx));
        text.push_str(&format!("{i},{w},{q},\"ok\",\"{}\"\n", motions(i)));
    }
    fs::write(&path, text).unwrap();
    path
}

fn check_map_legend(path: &Path) -> MapFigure<'static> {
    let map: &'static MapFile = Box::leak(Box::new(MapFile::read(path).unwrap()));
    let figure = MapFigure::new(map);
    let frame = image(&figure);
    let (boxes, _) = figure.legend_boxes();
    for r in &boxes {
        assert!(r.inside(&frame), "{r:?} leaves the image {frame:?}");
    }
    let mut drawn = boxes.clone();
    drawn.retain(|r| r.x1 > r.x0);
    assert_apart(&drawn, "legend");
    let svg = path.with_extension("svg");
    stickslip::output::figure::map::draw_map(map, &svg).unwrap();
    figure
}

#[test]
fn map_legend_shows_long_names_in_full() {
    register().unwrap();
    let long =
        "P_{3_31 0_11 3_13 4_33 3_31 0_11 3_13 4_33 3_33 4_33 3_33 4_33 3_33 4_33 3_33 4_33}^6";
    let two = format!("{long};P_{{3_33 4_33}}");
    let names = [
        long.to_string(),
        two.clone(),
        "NM".to_string(),
        "P_{3_33 4_33}".to_string(),
    ];
    let path = map_file("long.csv", 2, 2, |i| names[i].clone());
    let figure = check_map_legend(&path);
    // Every character of every name is drawn (wrapped, not cut).
    let svg = fs::read_to_string(path.with_extension("svg")).unwrap();
    let text: String = svg
        .split("<text")
        .skip(1)
        .filter_map(|t| t.split_once('>').and_then(|(_, r)| r.split_once("</text>")))
        .map(|(t, _)| t.to_string())
        .collect::<Vec<_>>()
        .join(" ");
    let squeeze = |s: &str| s.split_whitespace().collect::<String>();
    for name in [long.to_string(), two.replace(';', " + ")] {
        assert!(
            squeeze(&text).contains(&squeeze(&name)),
            "`{name}` not drawn in full"
        );
    }
    assert_eq!(
        figure.size(),
        (1500, 900),
        "four entries fit the default image"
    );
}

#[test]
fn map_legend_with_many_sets_grows_the_image_and_sums_the_rest() {
    register().unwrap();
    let path = map_file("many.csv", 10, 10, |i| {
        format!(
            "P_{{3_31 0_11 3_13 4_33 {}3_33 4_33}}^{}",
            "3_33 4_33 ".repeat(i % 7),
            i
        )
    });
    let figure = check_map_legend(&path);
    let (w, h) = figure.size();
    assert_eq!(w, 1500);
    assert!(h > 900, "the image grows for the legend ({h})");
    let svg = fs::read_to_string(path.with_extension("svg")).unwrap();
    assert!(
        svg.contains("… 41 more sets (41 points)"),
        "the rest summed"
    );
}
