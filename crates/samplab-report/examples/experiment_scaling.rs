//! Each experiment of `samplab reproduce` run alone on 1 thread and on 2 (and 4, 8, 16
//! where the machine has the cores): its median wall time, its speed-up and Amdahl's serial
//! fraction from the 1- and 2-thread medians, f = 2 T2 / T1 - 1, and what these predict for
//! the whole reproduction on 16 threads. The run shares its threads among experiments
//! (longest first), so it takes at least its work over the threads, the sum of the
//! experiments' one-thread times over 16, and at least its longest experiment alone on 16
//! threads, T1 (f + (1 - f) / 16), which no number of experiments beside it shortens: an
//! experiment whose serial part is long sets the run's time on a large machine however
//! well the rest scales. Rounds alternate the thread counts, experiment by experiment, so
//! that a slow spell of a noisy machine hits every column alike. Prints a Markdown table.
//!
//! Used by `bench/compare experiments`:
//!
//! cargo run --release -p samplab-report --example experiment_scaling -- [--rounds K] [--full] [--threads 1,2,..] [PAGE[/EXPERIMENT]...]

use std::sync::atomic::AtomicBool;
use std::time::Instant;

use samplab::Seed;
use samplab_report::{Ctx, Scale, UNWATCHED, paper};

/// The threads of the large machine the prediction is for.
const LARGE: f64 = 16.0;

/// The usage line after `why` (on stdout and exit code 0 for --help, else stderr and 2).
fn usage(why: &str, code: i32) -> ! {
    let text = format!(
        "experiment_scaling: {why}\nusage: experiment_scaling [--rounds K] [--full] [--threads 1,2,..] [PAGE[/EXPERIMENT]...]   (pages: {})",
        paper::keys().join(", ")
    );
    if code == 0 {
        println!("{text}");
    } else {
        eprintln!("{text}");
    }
    std::process::exit(code)
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let (mut rounds, mut scale, mut pages, mut threads) = (3usize, Scale::Fast, Vec::new(), None::<Vec<usize>>);
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--rounds" => {
                rounds = match args.next().and_then(|k| k.parse().ok()) {
                    Some(k) if k >= 1 => k,
                    _ => usage("--rounds takes a whole number of at least 1", 2),
                }
            }
            "--full" => scale = Scale::Full,
            "--threads" => {
                threads = args.next().and_then(|list| list.split(',').map(|t| t.parse().ok()).collect());
                if threads.as_ref().is_none_or(|t| t.is_empty() || t.contains(&0)) {
                    usage("--threads takes a list of thread counts, such as 2 or 1,2,4", 2);
                }
            }
            "-h" | "--help" => usage("each experiment alone on 1, 2, .. threads", 0),
            key if paper::keys().contains(&key.split('/').next().unwrap_or_default()) => pages.push(key.to_string()),
            other => usage(&format!("unknown argument or page '{other}'"), 2),
        }
    }
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let counts = threads.unwrap_or_else(|| [1, 2, 4, 8, 16].into_iter().filter(|&t| t <= cores.max(2)).collect());
    let pools: Vec<rayon::ThreadPool> = counts
        .iter()
        .map(|&t| rayon::ThreadPoolBuilder::new().num_threads(t).build().expect("a thread pool"))
        .collect();
    let papers = paper::all();
    let experiments: Vec<(String, &samplab_report::Experiment)> = papers
        .iter()
        .flat_map(|p| p.experiments.iter().map(move |e| (format!("{}/{}", p.key, e.id), e)))
        .filter(|(name, _)| pages.is_empty() || pages.iter().any(|k| name == k || name.starts_with(&format!("{k}/"))))
        .collect();
    if let Some(k) =
        pages.iter().find(|k| !experiments.iter().any(|(name, _)| name == *k || name.starts_with(&format!("{k}/"))))
    {
        usage(&format!("no experiment '{k}'"), 2);
    }
    let stop = AtomicBool::new(false);
    let mut seconds = vec![vec![Vec::new(); counts.len()]; experiments.len()];
    for round in 0..rounds {
        eprintln!("round {} of {rounds}", round + 1);
        for ((name, e), times) in experiments.iter().zip(&mut seconds) {
            for (pool, times) in pools.iter().zip(times.iter_mut()) {
                // the reproduction's own seed for this experiment
                let ctx = Ctx { scale, seed: Seed::DEFAULT.derive_str(name), watch: UNWATCHED, stop: &stop, task: 0 };
                let start = Instant::now();
                if let Err(err) = pool.install(|| (e.run)(&ctx)) {
                    eprintln!("experiment_scaling: {name}: {err}");
                    std::process::exit(1);
                }
                times.push(start.elapsed().as_secs_f64());
            }
        }
    }
    let medians: Vec<Vec<f64>> = seconds.into_iter().map(|t| t.into_iter().map(median).collect()).collect();
    let mut order: Vec<usize> = (0..experiments.len()).collect();
    order.sort_by(|&a, &b| medians[b][0].total_cmp(&medians[a][0]));
    println!(
        "samplab reproduce{}, each experiment alone: {cores} cores, {rounds} rounds, medians of wall time",
        if scale == Scale::Full { " --full" } else { "" }
    );
    let heads: Vec<String> = counts.iter().map(|t| format!("{t} thread{}", if *t == 1 { "" } else { "s" })).collect();
    let cells = |m: &[f64]| m.iter().map(|s| format!("{s:.2} s")).collect::<Vec<_>>().join(" | ");
    if !counts.starts_with(&[1, 2]) {
        // no serial fraction without the 1- and 2-thread times
        println!("| experiment | {} |\n|---|{}", heads.join(" | "), "---|".repeat(counts.len()));
        for &k in &order {
            println!("| {} | {} |", experiments[k].0, cells(&medians[k]));
        }
        return;
    }
    let serial = |m: &[f64]| 2.0 * m[1] / m[0] - 1.0;
    let large = |m: &[f64]| m[0] * (serial(m).max(0.0) + (1.0 - serial(m).max(0.0)) / LARGE);
    println!(
        "| experiment | {} | speed-up at 2 | serial fraction | alone on 16 threads (predicted) |",
        heads.join(" | ")
    );
    println!("|---|{}---|---|---|", "---|".repeat(counts.len()));
    for &k in &order {
        let m = &medians[k];
        println!(
            "| {} | {} | {:.2}x | {:.1}% | {:.2} s |",
            experiments[k].0,
            cells(m),
            m[0] / m[1],
            100.0 * serial(m),
            large(m)
        );
    }
    let work: f64 = medians.iter().map(|m| m[0]).sum();
    let (longest, bound) = order
        .iter()
        .map(|&k| (&experiments[k].0, large(&medians[k])))
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .expect("one experiment");
    let floor = (work / LARGE).max(bound);
    println!();
    println!(
        "On 16 threads the run takes at least {floor:.1} s, a speed-up of at most {:.1}x over its {work:.1} s on one thread: \
         its work over 16 threads is {:.1} s, its longest experiment alone ({longest}) {bound:.1} s.",
        work / floor,
        work / LARGE
    );
}
