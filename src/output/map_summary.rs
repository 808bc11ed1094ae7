//! The summary of a map run or merge: points done, time, points per label.

use std::path::Path;

use crate::study::map::Summary;

/// What `map` and `merge` print about the map in `out`: how many points
/// are done (now and before), the wall time, whether to resume, and the
/// count of each label.
pub fn text(s: &Summary, out: &Path) -> String {
    let mut text = format!(
        "{}: {} of {} grid points ({} computed now, {} already done) in {:.2} s{}\n",
        out.display(),
        s.already_done + s.computed,
        s.shard_points,
        s.computed,
        s.already_done,
        s.elapsed.as_secs_f64(),
        if s.complete {
            ""
        } else {
            " — incomplete: run again with --resume"
        }
    );
    for (label, count) in &s.labels {
        text.push_str(&format!("  {count:>6}  {label}\n"));
    }
    text
}
