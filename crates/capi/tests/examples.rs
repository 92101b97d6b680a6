//! The C, C++, Fortran and MPI examples, compiled against the real libdepo and run; the C one
//! also under valgrind, statically linked, and after `install.sh` through pkg-config and
//! through CMake's `find_package(depo)`; the headers compiled alone with every warning an error;
//! the Fortran module's argument checks.
//!
//! A missing compiler or tool fails the test, with the package to install. Setting its
//! `DEPO_SKIP_*` variable to 1 (`DEPO_SKIP_FORTRAN`, `DEPO_SKIP_MPI`, `DEPO_SKIP_CMAKE`,
//! `DEPO_SKIP_VALGRIND`, `DEPO_SKIP_C`; see [`TOOLS`]) skips the tests that need it instead, each with a `SKIPPED`
//! line on stderr: a skip is never a silent pass.

use std::path::{Path, PathBuf};
use std::process::Command;

mod common;
use common::{libdir, root, run};

fn out_dir(name: &str) -> PathBuf {
    let dir = libdir().join("ffi-examples").join(name);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The tools the examples need, the variable that skips the tests needing each when it is
/// missing, and the Debian packages that provide it.
const TOOLS: &[(&str, &str, &str)] = &[
    ("cc", "DEPO_SKIP_C", "gcc"),
    ("c++", "DEPO_SKIP_C", "g++"),
    ("pkg-config", "DEPO_SKIP_C", "pkg-config"),
    ("readelf", "DEPO_SKIP_C", "binutils"),
    ("valgrind", "DEPO_SKIP_VALGRIND", "valgrind"),
    ("gfortran", "DEPO_SKIP_FORTRAN", "gfortran"),
    ("mpicc", "DEPO_SKIP_MPI", "libopenmpi-dev"),
    ("mpirun", "DEPO_SKIP_MPI", "openmpi-bin"),
    ("cmake", "DEPO_SKIP_CMAKE", "cmake"),
];

/// True if `tool` runs. A missing tool fails the test with what to install, unless the tool's
/// `DEPO_SKIP_*` variable is set to 1: then the test says SKIPPED on stderr, where it shows
/// without `--nocapture` (written to the stream itself, which the test harness does not
/// capture), and returns without running the example.
fn have(tool: &str) -> bool {
    if Command::new(tool).arg("--version").output().is_ok_and(|o| o.status.success()) {
        return true;
    }
    let &(_, skip, package) = TOOLS.iter().find(|t| t.0 == tool).unwrap_or_else(|| panic!("{tool} is not in TOOLS"));
    let test = std::thread::current().name().unwrap_or("this test").to_string();
    if std::env::var_os(skip).is_some_and(|v| v == "1") {
        use std::io::Write;
        let line = format!("SKIPPED {test}: {tool} is not installed ({skip}=1)\n");
        let _ = std::io::stderr().write_all(line.as_bytes());
        return false;
    }
    panic!(
        "{tool} is not installed, so {test} cannot run: install it (on Debian and Ubuntu: \
         apt-get install {package}; .ci/run installs every tool the tests need), or set {skip}=1 \
         to skip the tests that need it"
    );
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

/// Every entry point's results on fixed inputs, bit for bit, against those stored in
/// `tests/golden/abi.txt`: a restructuring of the crates must leave the C ABI's answers
/// unchanged. After a change that is meant to alter results, `DEPO_BLESS=1` writes the file anew
/// (and the commit says why the numbers moved).
#[test]
fn abi_results_unchanged_bit_for_bit() {
    if !have("cc") {
        return;
    }
    let golden = root().join("crates/capi/tests/golden");
    let exe = out_dir("golden").join("abi");
    run(link_depo(
        c_flags(Command::new("cc").args(["-std=c11", &include("crates/capi/include")]))
            .arg(golden.join("abi.c"))
            .arg("-o")
            .arg(&exe),
    )
    .arg("-lm"));
    let out = String::from_utf8(run(&mut Command::new(&exe)).stdout).unwrap();
    let stored = golden.join("abi.txt");
    if std::env::var_os("DEPO_BLESS").is_some_and(|v| v == "1") {
        std::fs::write(&stored, &out).unwrap();
        return;
    }
    let expected = std::fs::read_to_string(&stored).unwrap();
    assert_eq!(out.lines().count(), expected.lines().count(), "abi.c printed another number of lines");
    if let Some((i, (got, want))) = out.lines().zip(expected.lines()).enumerate().find(|(_, (a, b))| a != b) {
        panic!("C ABI result changed at line {} of {}:\n  now:    {got}\n  stored: {want}", i + 1, stored.display());
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

/// The dynamic section of an ELF file, as `readelf -d` prints it.
fn dynamic_section(file: &Path) -> String {
    String::from_utf8(run(Command::new("readelf").arg("-d").arg(file)).stdout).unwrap()
}

/// Installs into a fresh prefix, links the C example with nothing but `pkg-config --cflags
/// --libs depo`, and runs it without `LD_LIBRARY_PATH`: what a user of the README does.
#[test]
fn installed_library_links_with_pkg_config_and_runs() {
    if !have("cc") || !have("pkg-config") || !have("readelf") {
        return;
    }
    let dir = out_dir("install");
    let prefix = dir.join("prefix");
    let _ = std::fs::remove_dir_all(&prefix);
    run(Command::new("bash").arg(root().join("crates/capi/install.sh")).arg(&prefix).arg(libdir()));
    let lib = prefix.join("lib");
    let soname = env!("DEPO_SONAME");

    // The library carries its SONAME, installed as the versioned file with the two links.
    let real = lib.join(format!("libdepo.so.{}", env!("CARGO_PKG_VERSION")));
    assert!(dynamic_section(&real).contains(&format!("Library soname: [{soname}]")), "{}", dynamic_section(&real));
    assert_eq!(std::fs::read_link(lib.join(soname)).unwrap(), Path::new(real.file_name().unwrap()));
    assert_eq!(std::fs::read_link(lib.join("libdepo.so")).unwrap(), Path::new(soname));

    let pc_path = lib.join("pkgconfig");
    let flags = run(Command::new("pkg-config").env("PKG_CONFIG_PATH", &pc_path).args(["--cflags", "--libs", "depo"]));
    let flags = String::from_utf8(flags.stdout).unwrap();
    let version = run(Command::new("pkg-config").env("PKG_CONFIG_PATH", &pc_path).args(["--modversion", "depo"]));
    assert_eq!(String::from_utf8(version.stdout).unwrap().trim(), env!("CARGO_PKG_VERSION"));
    let exe = dir.join("box");
    run(c_flags(Command::new("cc").args(["-std=c11", &include("examples/c")]))
        .arg(root().join("examples/c/box.c"))
        .args(flags.split_whitespace())
        .args(["-lm", "-o"])
        .arg(&exe));

    // The program asks for the SONAME and finds it in the prefix by itself.
    let dynamic = dynamic_section(&exe);
    assert!(dynamic.contains(&format!("Shared library: [{soname}]")), "{dynamic}");
    assert!(dynamic.contains(&lib.display().to_string()), "no run path to {}:\n{dynamic}", lib.display());
    let out = run(Command::new(&exe).env_remove("LD_LIBRARY_PATH").arg("2000"));
    check_report(&String::from_utf8_lossy(&out.stdout));
}

/// Installs into a fresh prefix and builds the C example as a CMake project would:
/// `find_package(depo REQUIRED)` and `target_link_libraries(box depo::depo)` (and the static
/// target), then runs both without `LD_LIBRARY_PATH`. A version from another ABI series is
/// refused.
#[test]
fn installed_library_builds_with_cmake() {
    if !have("cc") || !have("cmake") {
        return;
    }
    let dir = out_dir("cmake");
    let (prefix, project, build) = (dir.join("prefix"), dir.join("project"), dir.join("build"));
    for d in [&prefix, &project, &build] {
        let _ = std::fs::remove_dir_all(d);
    }
    run(Command::new("bash").arg(root().join("crates/capi/install.sh")).arg(&prefix).arg(libdir()));
    assert!(prefix.join("lib/cmake/depo/depoConfig.cmake").exists());
    assert!(prefix.join("lib/cmake/depo/depoConfigVersion.cmake").exists());

    let version = format!("{}.{}", env!("CARGO_PKG_VERSION_MAJOR"), env!("CARGO_PKG_VERSION_MINOR"));
    let cmakelists = |requested: &str| {
        format!(
            "cmake_minimum_required(VERSION 3.16)\nproject(depo_box C)\n\
             find_package(depo {requested} REQUIRED)\n\
             add_executable(box \"{src}\")\n\
             target_link_libraries(box PRIVATE depo::depo m)\n\
             add_executable(box_static \"{src}\")\n\
             target_link_libraries(box_static PRIVATE depo::depo_static m)\n",
            src = root().join("examples/c/box.c").display()
        )
    };
    std::fs::create_dir_all(&project).unwrap();
    let configure = |requested: &str| {
        std::fs::write(project.join("CMakeLists.txt"), cmakelists(requested)).unwrap();
        let _ = std::fs::remove_dir_all(&build);
        Command::new("cmake")
            .arg("-S")
            .arg(&project)
            .arg("-B")
            .arg(&build)
            .arg(format!("-DCMAKE_PREFIX_PATH={}", prefix.display()))
            .arg("-DCMAKE_C_FLAGS=-std=c11 -Wall -Wextra -Wpedantic -Werror")
            .output()
            .unwrap()
    };

    // Another ABI series is refused at configure time.
    let other = configure(&format!("{}.{}", env!("CARGO_PKG_VERSION_MAJOR"), 99));
    let stderr = String::from_utf8_lossy(&other.stderr);
    assert!(!other.status.success() && stderr.contains("compatible"), "find_package(depo x.99) should fail:\n{stderr}");

    let out = configure(&version);
    assert!(
        out.status.success(),
        "cmake configure failed\nstdout:\n{}\nstderr:\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    run(Command::new("cmake").arg("--build").arg(&build));
    for exe in ["box", "box_static"] {
        let out = run(Command::new(build.join(exe)).env_remove("LD_LIBRARY_PATH").arg("2000"));
        check_report(&String::from_utf8_lossy(&out.stdout));
    }
    if have("readelf") {
        let dynamic = dynamic_section(&build.join("box"));
        assert!(dynamic.contains(&format!("Shared library: [{}]", env!("DEPO_SONAME"))), "{dynamic}");
        assert!(!dynamic_section(&build.join("box_static")).contains("libdepo"));
    }
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

/// Hussein et al.'s deposition velocity and chance for the particles of
/// `tests/wall_function/hussein.*` as the tracker's `wall_function` functions give them, bit
/// for bit, from the lines a program printed; and the refused particle's status and message.
fn check_hussein(stdout: &str) {
    use depo_tracker::wall_function::{deposition_probability, deposition_velocity, Correlation};
    use depo_tracker::{Aerodynamics, Air, Orientation};
    let air = Air { temperature: 293.15, pressure: 101_325.0, density: 1.204, viscosity: 1.81e-5 };
    let mut lines = 0;
    for line in stdout.lines().filter(|l| l.starts_with("hussein ")) {
        let w: Vec<f64> = line.split_whitespace().skip(1).map(|x| x.parse().unwrap()).collect();
        let orientation = [Orientation::Floor, Orientation::Ceiling, Orientation::Wall][w[0] as usize];
        let (u, d, rho, layer, dt, v, p) = (w[1], w[2], w[3], w[4], w[5], w[6], w[7]);
        let aero = Aerodynamics::new(d, rho, &air, 9.80665);
        let expected = deposition_velocity(Correlation::Hussein, &aero, &air, u, orientation);
        assert_eq!(v.to_bits(), expected.to_bits(), "{line}: Rust gives {expected:e}");
        let chance = deposition_probability(expected, layer, dt);
        assert_eq!(p.to_bits(), chance.to_bits(), "{line}: Rust gives {chance:e}");
        lines += 1;
    }
    assert_eq!(lines, 12, "{stdout}");
    let refused = stdout.lines().find(|l| l.starts_with("refused ")).expect("a refused line");
    assert!(refused.starts_with("refused 2 -1") && refused.contains("wall units"), "{refused}");
}

/// Hussein et al.'s wall function from C, C++ (depo.hpp) and Fortran (the module): the
/// tracker's values, the correlation's constant in each header, and the refusal of a particle
/// larger than the model's layer.
#[test]
fn hussein_s_wall_function_from_c_cpp_and_fortran_is_the_tracker_s() {
    let dir = out_dir("hussein");
    let src = root().join("crates/capi/tests/wall_function");
    if have("cc") {
        let exe = dir.join("hussein-c");
        run(link_depo(
            c_flags(Command::new("cc").args(["-std=c11", &include("crates/capi/include")]))
                .arg(src.join("hussein.c"))
                .arg("-o")
                .arg(&exe),
        ));
        check_hussein(&String::from_utf8(run(&mut Command::new(&exe)).stdout).unwrap());
    }
    if have("c++") {
        let exe = dir.join("hussein-cpp");
        run(link_depo(
            c_flags(Command::new("c++").args(["-std=c++11", &include("crates/capi/include")]))
                .arg(src.join("hussein.cpp"))
                .arg("-o")
                .arg(&exe),
        ));
        check_hussein(&String::from_utf8(run(&mut Command::new(&exe)).stdout).unwrap());
    }
    if have("gfortran") {
        let exe = dir.join("hussein-f");
        run(link_depo(
            Command::new("gfortran")
                .args(["-std=f2018", "-Wall", "-Wextra", "-Werror", "-J"])
                .arg(&dir)
                .arg(root().join("crates/capi/fortran/depo.f90"))
                .arg(src.join("hussein.f90"))
                .arg("-o")
                .arg(&exe),
        ));
        check_hussein(&String::from_utf8(run(&mut Command::new(&exe)).stdout).unwrap());
    }
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

/// Without gfortran or mpicc on the path, the Fortran and MPI tests fail and say what to
/// install; with their `DEPO_SKIP_*` variable set they pass and print a SKIPPED line that shows
/// in the normal (captured) test output. Runs this test binary on those two tests with an empty
/// `PATH`.
#[test]
fn missing_compilers_fail_or_are_skipped_visibly() {
    let exe = std::env::current_exe().unwrap();
    let empty = exe.parent().unwrap().join("depo-empty-path");
    std::fs::create_dir_all(&empty).unwrap();
    for (test, tool, skip) in [
        ("fortran_example_runs", "gfortran", "DEPO_SKIP_FORTRAN"),
        ("mpi_example_runs_on_two_ranks", "mpicc", "DEPO_SKIP_MPI"),
    ] {
        let child = |skipping: bool| {
            let mut cmd = Command::new(&exe);
            cmd.args([test, "--exact"]).env("PATH", &empty);
            for &(_, var, _) in TOOLS {
                cmd.env_remove(var);
            }
            if skipping {
                cmd.env(skip, "1");
            }
            let out = cmd.output().unwrap();
            let text = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
            (out.status.success(), String::from_utf8_lossy(&out.stderr).into_owned(), text)
        };
        let (passed, _, text) = child(false);
        assert!(!passed, "{test} passed without {tool}:\n{text}");
        assert!(text.contains(&format!("{tool} is not installed")) && text.contains("apt-get install"), "{text}");
        assert!(text.contains(&format!("{skip}=1")), "the failure should name {skip}:\n{text}");
        let (passed, stderr, text) = child(true);
        assert!(passed, "{test} with {skip}=1 should pass:\n{text}");
        assert!(stderr.contains(&format!("SKIPPED {test}: {tool} is not installed ({skip}=1)")), "{text}");
    }
}
