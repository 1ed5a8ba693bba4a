//! The report crate's master input ([`rollfit_report::master_input`]): a
//! joint fit's DMA file read as `rollfit master` reads it, checked against
//! io's own grouping of the same file and the fit library's ranges.

use std::fs;

use rollfit_io::chain;
use rollfit_io::dma::{DmaInput, group_isotherms};
use rollfit_report::master_input::joint;
use rollfit_testkit::eplexor::{eplexor_csv, eplexor_points, eplexor_rows};
use rollfit_testkit::files::TempDir;
use rollfit_testkit::run::assert_contains;
use rollfit_testkit::workbook::xlsx;

/// A joint fit's DMA file is read and grouped as `rollfit
/// master` reads it, from a CSV and a workbook alike; a file without
/// temperatures is one isotherm at T_ref, refused without one; a point the
/// fit library refuses is named by its line.
#[test]
fn a_joint_fits_dma_file_is_read_as_the_master_curve_reads_it() {
    let dir = TempDir::new("joint");
    let points = eplexor_points(&[0.0, 20.0, 40.0, 60.0]);
    let csv = dir.write("sweep.csv", eplexor_csv(&points));
    let book = dir.write(
        "sweep.xlsx",
        xlsx(&[("Sheet1", eplexor_rows(&points, false))]),
    );
    let data = DmaInput::file(&csv).read(0.5, None).unwrap();
    let grouped = group_isotherms(data, None).unwrap();
    assert_eq!(grouped.isotherms.len(), 4);
    for path in [&csv, &book] {
        let joint = joint::read(path, 0.5, None)
            .unwrap_or_else(|e| panic!("{}: {}", path.display(), chain(&e)));
        assert_eq!(joint.rows.source(), path.display().to_string());
        assert_eq!(joint.rows.isotherms(), &grouped.isotherms[..]);
        assert_eq!(joint.rows.len(), points.len());
    }

    // Without temperatures: one isotherm at T_ref, or refused.
    let mut untimed = String::from("f_Hz,E_storage_MPa,E_loss_MPa\n");
    for &(_, f, s, l) in points.iter().filter(|p| p.0 == 20.0) {
        untimed += &format!("{f:e},{s:e},{l:e}\n");
    }
    let untimed = dir.write("untimed.csv", untimed);
    let joint = joint::read(&untimed, 0.5, Some(20.0)).unwrap();
    assert_eq!(joint.rows.temperatures(), [20.0]);
    let err = chain(&joint::read(&untimed, 0.5, None).unwrap_err());
    assert_contains(
        &err,
        &["untimed.csv", "no point has a temperature", "`T_ref`"],
    );

    // E′ in MPa read as Pa: below the library's 1 Pa, named by its line.
    let text = fs::read_to_string(&csv).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let fields: Vec<&str> = lines[3].split(',').collect();
    lines[3] = format!("{},{},5e-7,{}", fields[0], fields[1], fields[3]);
    let small = dir.write("small.csv", lines.join("\n") + "\n");
    let err = chain(&joint::read(&small, 0.5, None).unwrap_err());
    assert_contains(
        &err,
        &["DMA file", "small.csv", "line 4", "E′", "1 … 1e13 Pa"],
    );

    // An isotherm of one point: the line of that point.
    let single = dir.write("single.csv", format!("{}\n80,1,3,0.5\n", text.trim_end()));
    let err = chain(&joint::read(&single, 0.5, None).unwrap_err());
    let last = text.lines().count() + 1;
    assert_contains(
        &err,
        &["single.csv", &format!("line {last}"), "at least two"],
    );
}
