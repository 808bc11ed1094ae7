use stickslip_codegen::generate_source;

fn on_small_stack<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> T {
    std::thread::Builder::new().stack_size(2 << 20).spawn(f).unwrap().join().unwrap()
}

const COULOMB: &str = r#"model coulomb {
    param m = 1.0, > 0;
    param d = 0.05, >= 0;
    param c = 1.0, > 0;
    param A = 0.5;
    param W = 1.0, > 0;
    param mu = 0.3;
    param k = 0.1;
    param V = 1.0;
    oscillator { mass: m, damping: d, stiffness: c, forcing: A, frequency: W }
    boundary Sigma1: v = V;
    domain 1: v > Sigma1 => mu + k * (v - V);
    domain 2: v < Sigma1 => mu - k * (V - v);
}
"#;

#[test]
fn exp_deep() {
    let which = std::env::var("WHICH").unwrap_or_default();
    let src = match which.as_str() {
        "paren" => COULOMB.replace("forcing: A", &format!("forcing: {}A{}", "(".repeat(5000), ")".repeat(5000))),
        "neg" => COULOMB.replace("forcing: A", &format!("forcing: {}A", "- ".repeat(5000))),
        "sum" => COULOMB.replace("forcing: A", &format!("forcing: A{}", (1..=std::env::var("N").map(|n| n.parse().unwrap()).unwrap_or(50000)).map(|i| format!(" + 0.00001 * m * {i}.0")).collect::<String>())),
        _ => std::fs::read_to_string("../models/stribeck.ssm").unwrap().replace("vs = 0.4", "vs = 0.1"),
    };
    let t = std::time::Instant::now();
    let r = on_small_stack(move || generate_source(&src, "x.ssm").map(|g| g.code.len()));
    eprintln!("{:?} {:?}", t.elapsed(), r.map_err(|e| e[..e.len().min(2000)].to_string()));
}
