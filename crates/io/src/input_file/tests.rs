use super::*;

#[test]
fn limits_are_bytes_or_powers_of_1024() {
    assert_eq!(parse_limit("1000"), Some(1000));
    assert_eq!(parse_limit(" 500M "), Some(500 << 20));
    assert_eq!(parse_limit("2G"), Some(2 << 30));
    assert_eq!(parse_limit("2g"), Some(2 << 30));
    assert_eq!(parse_limit("2GiB"), Some(2 << 30));
    assert_eq!(parse_limit("2GB"), Some(2 << 30));
    assert_eq!(parse_limit("64k"), Some(64 << 10));
    assert_eq!(parse_limit("1T"), Some(1 << 40));
    assert_eq!(parse_limit("700B"), Some(700));
    for bad in [
        "",
        "0",
        "0G",
        "G",
        "-5",
        "1.5G",
        "2X",
        "iB",
        "5iB",
        "1e9",
        "2 G",
        "99999999999999999999",
        "20000000T",
    ] {
        assert_eq!(parse_limit(bad), None, "{bad:?}");
    }
}

#[test]
fn sizes_read_as_bytes_and_binary_units() {
    assert_eq!(size_text(1000), "1000 bytes");
    assert_eq!(size_text(DEFAULT_LIMIT), "1073741824 bytes (1 GiB)");
    assert_eq!(size_text(1536), "1536 bytes (1.5 KiB)");
}

/// A folder and a path that does not exist; the devices and FIFOs run
/// through the binary (tests/limits_cli.rs), where the limit variable can
/// be set per process.
#[test]
fn a_folder_is_refused_unopened_and_a_missing_file_keeps_the_readers_words() {
    let dir = std::env::temp_dir().join(format!("rollfit-input-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let unreadable = |source| err!("{}: {source}", dir.join("x").display()).system(source);
    let m = read_input(&dir, "data file", unreadable)
        .unwrap_err()
        .to_string();
    assert!(
        m.contains("data file ") && m.ends_with("is a folder, not a file; name a file inside it"),
        "{m}"
    );
    let e = read_input(&dir.join("absent.csv"), "data file", unreadable).unwrap_err();
    assert_eq!(e.kind(), crate::error::ErrorKind::System, "{e:?}");
    std::fs::write(dir.join("a.csv"), "v,mu\n").unwrap();
    assert_eq!(
        read_input(&dir.join("a.csv"), "data file", unreadable).unwrap(),
        b"v,mu\n"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[cfg(unix)]
#[test]
fn an_endless_device_is_refused_unopened() {
    let m = read_input(Path::new("/dev/zero"), "DMA file", |source| {
        err!("/dev/zero: {source}").system(source)
    })
    .unwrap_err()
    .to_string();
    assert!(
        m.starts_with(
            "DMA file /dev/zero is a character device (such as /dev/zero), not a regular file"
        ),
        "{m}"
    );
}
