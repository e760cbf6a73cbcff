//! README.md's supported-codes table is the one the code generates (`cargo xtask readme`).

#[test]
fn readme_code_table_matches_the_code() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../README.md");
    let text = std::fs::read_to_string(&path).unwrap();
    let start = text
        .find("<!-- codes:start -->\n")
        .expect("README has the codes section")
        + 21;
    let end = text
        .find("<!-- codes:end -->")
        .expect("README has the codes section end");
    assert_eq!(
        &text[start..end],
        vcnc::profile::supported_codes_markdown(),
        "README.md's code table is stale: run `cargo xtask readme`"
    );
}
