fn main() {
    let path = std::env::args().nth(1).expect("path");
    match stickslip_codegen::generate_file(std::path::Path::new(&path), &path) {
        Ok(g) => print!("{}", g.code),
        Err(e) => {
            eprint!("{e}");
            std::process::exit(1)
        }
    }
}
