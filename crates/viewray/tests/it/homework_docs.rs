//! docs/homework.md shows real output: every `$ viewray ...` (with `| head -N` or `| tail
//! -N`, its first or last lines) and `$ cat FILE` in its console blocks is run from the
//! repository's root, and what follows it in the block is what it prints, to the byte.

use crate::support;

use std::process::Command;

/// The commands of `text`'s console blocks, each with the lines shown after it (the
/// block's indentation removed).
fn examples(text: &str) -> Vec<(String, String)> {
    let mut examples = Vec::new();
    let mut in_block = None;
    for line in text.lines() {
        let trimmed = line.trim_start();
        let indent = line.len() - trimmed.len();
        match in_block {
            None if trimmed == "```console" => in_block = Some(indent),
            None => {}
            Some(_) if trimmed == "```" => in_block = None,
            Some(block_indent) => {
                let line = line.get(block_indent..).unwrap_or("");
                if let Some(command) = line.strip_prefix("$ ") {
                    examples.push((command.to_owned(), String::new()));
                } else if let Some((_, shown)) = examples.last_mut() {
                    shown.push_str(line);
                    shown.push('\n');
                }
            }
        }
    }
    examples
}

#[test]
fn every_example_of_the_homework_walkthrough_prints_what_it_shows() {
    let root = support::repository();
    let text = std::fs::read_to_string(root.join("docs/homework.md")).unwrap();
    let mut checked = 0;
    for (command, shown) in examples(&text) {
        let words: Vec<&str> = command.split_whitespace().collect();
        let printed = match words.as_slice() {
            // `| head -N` and `| tail -N` show the first or last lines of the output.
            ["viewray", args @ .., "|", end @ ("head" | "tail"), count] => {
                let out = support::viewray_in(&root, args);
                assert!(out.status.success(), "$ {command}");
                let count: usize = count.trim_start_matches('-').parse().unwrap();
                let text = String::from_utf8(out.stdout).unwrap();
                let lines: Vec<&str> = text.lines().collect();
                let shown_lines = if *end == "head" {
                    &lines[..count.min(lines.len())]
                } else {
                    &lines[lines.len().saturating_sub(count)..]
                };
                shown_lines
                    .iter()
                    .map(|l| format!("{l}\n"))
                    .collect::<String>()
                    .into_bytes()
            }
            ["viewray", args @ ..] => support::viewray_in(&root, args).stdout,
            ["cat", file] if root.join(file).is_file() => std::fs::read(root.join(file)).unwrap(),
            // Running the student's program shows that it prints the buggy answers the
            // walkthrough checks (where Python is installed).
            ["python3", program, ">", _] => match Command::new("python3")
                .arg(program)
                .current_dir(&root)
                .output()
            {
                Ok(out) => {
                    let expected = std::fs::read(root.join("fixtures/homework/answers/v_sign.txt"));
                    assert_eq!(out.stdout, expected.unwrap(), "{command}");
                    checked += 1;
                    continue;
                }
                Err(_) => continue,
            },
            _ => continue,
        };
        let printed = String::from_utf8(printed).unwrap();
        // A blank line ends a block's output before the prose resumes.
        assert_eq!(printed.trim_end(), shown.trim_end(), "$ {command}");
        checked += 1;
    }
    assert!(checked >= 10, "only {checked} examples checked");
}
