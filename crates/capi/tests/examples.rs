//! The C, C++, Fortran and MPI examples, compiled against the real libdepo and run; the C one
//! also under valgrind, statically linked, and through pkg-config after `install.sh`; the
//! headers compiled alone with every warning an error; the Fortran module's argument checks.
//!
//! A missing compiler or tool fails the test under CI (`CI` set; `.ci/run` installs them) and
//! is reported and skipped elsewhere.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..").canonicalize().unwrap()
}

/// Builds libdepo in the profile of this test binary and returns the directory holding it.
fn libdir() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        // target/<profile>/deps/examples-<hash>
        let exe = std::env::current_exe().unwrap();
        let profile_dir = exe.parent().unwrap().parent().unwrap().to_path_buf();
        let release = profile_dir.file_name().is_some_and(|n| n == "release");
        let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
        let mut build = Command::new(cargo);
        build.current_dir(root()).args(["build", "-q", "-p", "depo-capi"]);
        if release {
            build.arg("--release");
        }
        let status = build.status().expect("cargo build -p depo-capi");
        assert!(status.success(), "building libdepo failed");
        assert!(profile_dir.join("libdepo.so").exists() && profile_dir.join("libdepo.a").exists());
        profile_dir
    })
}

fn out_dir(name: &str) -> PathBuf {
    let dir = libdir().join("ffi-examples").join(name);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// True if `tool` runs; otherwise fails under CI, or says why the test is skipped.
fn have(tool: &str) -> bool {
    let found = Command::new(tool).arg("--version").output().is_ok_and(|o| o.status.success());
    if !found {
        assert!(std::env::var_os("CI").is_none(), "{tool} is missing; .ci/run installs it");
        eprintln!("skipping: {tool} is not installed (.ci/run installs it)");
    }
    found
}

fn run(cmd: &mut Command) -> Output {
    let out = cmd.output().unwrap_or_else(|e| panic!("{cmd:?}: {e}"));
    assert!(
        out.status.success(),
        "{cmd:?} failed\nstdout:\n{}\nstderr:\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// The whole number that follows the word `key` in the examples' output.
fn field(stdout: &str, key: &str) -> u64 {
    stdout
        .lines()
        .flat_map(|line| {
            let words: Vec<&str> = line.split_whitespace().collect();
            (1..words.len())
                .filter(|&i| words[i - 1] == key)
                .filter_map(|i| words[i].parse().ok())
                .collect::<Vec<u64>>()
        })
        .next()
        .unwrap_or_else(|| panic!("no '{key} <number>' in:\n{stdout}"))
}

/// Checks an example's report: particles conserved, some deposited, some rebounds, none invalid.
fn check_report(stdout: &str) {
    let injected = field(stdout, "injected");
    let airborne = field(stdout, "airborne");
    let deposited = field(stdout, "deposited");
    assert_eq!(airborne + deposited, injected, "{stdout}");
    assert!(deposited > 0 && airborne > 0, "{stdout}");
    assert_eq!(field(stdout, "captured"), deposited, "{stdout}");
    assert!(field(stdout, "rebound") > injected, "{stdout}");
    assert_eq!(field(stdout, "invalid"), 0, "{stdout}");
}

fn c_flags(cmd: &mut Command) -> &mut Command {
    cmd.args(["-Wall", "-Wextra", "-Wpedantic", "-Werror"])
}

fn link_depo(cmd: &mut Command) -> &mut Command {
    let lib = libdir().display().to_string();
    cmd.arg(format!("-L{lib}")).arg("-ldepo").arg(format!("-Wl,-rpath,{lib}"))
}

fn include(sub: &str) -> String {
    format!("-I{}", root().join(sub).display())
}

#[test]
fn headers_compile_alone() {
    if !have("cc") || !have("c++") {
        return;
    }
    let dir = out_dir("headers");
    std::fs::write(dir.join("c.c"), "#include \"depo.h\"\nint main(void) { return DEPO_OK; }\n").unwrap();
    std::fs::write(dir.join("h.cpp"), "#include \"depo.h\"\nint main() { return DEPO_OK; }\n").unwrap();
    std::fs::write(dir.join("hpp.cpp"), "#include \"depo.hpp\"\nint main() { return DEPO_OK; }\n").unwrap();
    for std in ["-std=c99", "-std=c11"] {
        run(c_flags(Command::new("cc").arg(std).arg(include("crates/capi/include")).arg("-c").arg(dir.join("c.c")))
            .arg("-o")
            .arg(dir.join("c.o")));
    }
    run(c_flags(
        Command::new("c++").args(["-std=c++11", &include("crates/capi/include"), "-c"]).arg(dir.join("h.cpp")),
    )
    .arg("-o")
    .arg(dir.join("h.o")));
    for std in ["-std=c++11", "-std=c++17"] {
        run(c_flags(Command::new("c++").args([std, &include("crates/capi/include"), "-c"]).arg(dir.join("hpp.cpp")))
            .arg("-o")
            .arg(dir.join("hpp.o")));
    }
}

#[test]
fn c_example_runs_and_is_clean_under_valgrind() {
    if !have("cc") {
        return;
    }
    let exe = out_dir("c").join("box");
    run(link_depo(
        c_flags(Command::new("cc").args(["-std=c11", "-g", &include("crates/capi/include"), &include("examples/c")]))
            .arg(root().join("examples/c/box.c"))
            .arg("-o")
            .arg(&exe),
    )
    .arg("-lm"));
    let out = run(Command::new(&exe).arg("5000"));
    let stdout = String::from_utf8_lossy(&out.stdout);
    check_report(&stdout);
    assert!(stdout.contains("rejected: invalid wall-law parameter kappa1"), "{stdout}");
    // The deposition map adds up, and gravity puts most deposits on the floor (z0).
    let map_line = stdout.lines().find(|l| l.starts_with("deposited per wall")).expect("deposition map line");
    let map: Vec<u64> = map_line.rsplit(':').next().unwrap().split_whitespace().map(|x| x.parse().unwrap()).collect();
    assert_eq!(map.iter().sum::<u64>(), field(&stdout, "deposited"), "{stdout}");
    assert!(map[4] > map.iter().sum::<u64>() / 2, "floor should dominate: {map_line}");

    if have("valgrind") {
        let out = run(Command::new("valgrind")
            .args(["--error-exitcode=99", "--leak-check=full", "--errors-for-leak-kinds=definite,indirect", "-q"])
            .arg(&exe)
            .arg("300"));
        check_report(&String::from_utf8_lossy(&out.stdout));
    }
}

#[test]
fn c_example_links_statically() {
    if !have("cc") {
        return;
    }
    let exe = out_dir("c-static").join("box");
    run(c_flags(Command::new("cc").args(["-std=c11", &include("crates/capi/include"), &include("examples/c")]))
        .arg(root().join("examples/c/box.c"))
        .arg(libdir().join("libdepo.a"))
        .args(["-lpthread", "-ldl", "-lm", "-o"])
        .arg(&exe));
    check_report(&String::from_utf8_lossy(&run(Command::new(&exe).arg("2000")).stdout));
}

#[test]
fn installed_library_is_found_by_pkg_config() {
    if !have("cc") || !have("pkg-config") {
        return;
    }
    let prefix = out_dir("install").join("prefix");
    run(Command::new("bash").arg(root().join("crates/capi/install.sh")).arg(&prefix).arg(libdir()));
    let pc_path = prefix.join("lib/pkgconfig");
    let flags = run(Command::new("pkg-config").env("PKG_CONFIG_PATH", &pc_path).args(["--cflags", "--libs", "depo"]));
    let flags = String::from_utf8(flags.stdout).unwrap();
    let version = run(Command::new("pkg-config").env("PKG_CONFIG_PATH", &pc_path).args(["--modversion", "depo"]));
    assert_eq!(String::from_utf8(version.stdout).unwrap().trim(), env!("CARGO_PKG_VERSION"));
    let exe = out_dir("install").join("box");
    run(c_flags(Command::new("cc").args(["-std=c11", &include("examples/c")]))
        .arg(root().join("examples/c/box.c"))
        .args(flags.split_whitespace())
        .arg(format!("-Wl,-rpath,{}", prefix.join("lib").display()))
        .args(["-lm", "-o"])
        .arg(&exe));
    check_report(&String::from_utf8_lossy(&run(Command::new(&exe).arg("2000")).stdout));
}

#[test]
fn cpp_example_runs() {
    if !have("c++") {
        return;
    }
    let exe = out_dir("cpp").join("box");
    run(link_depo(
        c_flags(Command::new("c++").args(["-std=c++17", &include("crates/capi/include")]))
            .arg(root().join("examples/cpp/box.cpp"))
            .arg("-o")
            .arg(&exe),
    ));
    let out = run(Command::new(&exe).arg("5000"));
    let stdout = String::from_utf8_lossy(&out.stdout);
    check_report(&stdout);
    assert!(stdout.contains("rejected: unknown wall-law preset 'granite'"), "{stdout}");
}

#[test]
fn fortran_example_runs() {
    if !have("gfortran") {
        return;
    }
    let dir = out_dir("fortran");
    let exe = dir.join("box");
    run(link_depo(
        Command::new("gfortran")
            .args(["-std=f2018", "-Wall", "-Wextra", "-Werror", "-J"])
            .arg(&dir)
            .arg(root().join("crates/capi/fortran/depo.f90"))
            .arg(root().join("examples/fortran/box.f90"))
            .arg("-o")
            .arg(&exe),
    ));
    let out = run(Command::new(&exe).arg("5000"));
    let stdout = String::from_utf8_lossy(&out.stdout);
    check_report(&stdout);
    assert!(stdout.contains("rejected: invalid wall-law parameter mu = -1"), "{stdout}");
    assert!(stdout.contains("e(1 m/s) =  0.73199"), "{stdout}");
}

/// The Fortran module's argument checks (`tests/fortran/checks.f90`): wrong sizes, partial
/// sets of optional arguments and a missing normal return their status and change nothing;
/// under valgrind too, so that no array is read or written past its end.
#[test]
fn fortran_module_checks_every_argument() {
    if !have("gfortran") {
        return;
    }
    let dir = out_dir("fortran-checks");
    let exe = dir.join("checks");
    run(link_depo(
        Command::new("gfortran")
            // The checks compare reals exactly on purpose: a failed call changes nothing.
            .args(["-std=f2018", "-Wall", "-Wextra", "-Werror", "-Wno-compare-reals", "-g", "-J"])
            .arg(&dir)
            .arg(root().join("crates/capi/fortran/depo.f90"))
            .arg(root().join("crates/capi/tests/fortran/checks.f90"))
            .arg("-o")
            .arg(&exe),
    ));
    let out = run(&mut Command::new(&exe));
    assert!(String::from_utf8_lossy(&out.stdout).contains("fortran checks passed"));
    if have("valgrind") {
        run(Command::new("valgrind").args(["--error-exitcode=99", "-q"]).arg(&exe));
    }
}

#[test]
fn mpi_example_runs_on_two_ranks() {
    if !have("mpicc") || !have("mpirun") {
        return;
    }
    let exe = out_dir("mpi").join("box");
    run(link_depo(
        c_flags(Command::new("mpicc").args(["-std=c11", &include("crates/capi/include"), &include("examples/c")]))
            .arg(root().join("examples/mpi/box_mpi.c"))
            .arg("-o")
            .arg(&exe),
    )
    .arg("-lm"));
    let out = run(Command::new("mpirun")
        .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
        .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
        .args(["--oversubscribe", "-np", "2"])
        .arg(&exe)
        .arg("3000"));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("ranks 2 injected 6000"), "{stdout}");
    check_report(&stdout);
}
