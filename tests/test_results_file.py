"""A batch's results file (foon2asp.batch.results_file): one writer at a time, and a header that --resume checks."""

from __future__ import annotations

import json

from foon2asp.batch.results_file import ResultFile, read_header, read_results
from helpers import one_line_error
from helpers import run_cli as run


def test_second_writer_is_refused(tmp_path):
    out = tmp_path / "r.jsonl"
    with ResultFile(out):
        msg = one_line_error(run("batch", "--goals", "all", "--output", out, "--resume", "--no-progress"))
    assert "in use by another running batch" in msg


def test_header_records_the_configuration_and_resume_checks_it(tmp_path):
    out = tmp_path / "r.jsonl"
    assert run("batch", "--goal", "tomato salad", "--output", out, "--no-progress").exit_code == 0
    first = json.loads(out.read_text().splitlines()[0])
    assert first["foon2asp_results"] == 1
    config = read_header(out)
    assert config["objective"] == ["units"] and len(config["input_sha256"]) == 64
    assert len(read_results(out)) == 1
    msg = one_line_error(run("batch", "--goals", "all", "--output", out, "--resume", "--objective", "success"))
    assert "differs in: objective" in msg
    msg = one_line_error(run("batch", "--goals", "all", "--output", out, "--resume", "--time-limit", "5"))
    assert "differs in: time_limit" in msg
    res = run("batch", "--goals", "all", "--output", out, "--resume", "--no-progress")
    assert res.exit_code == 0 and "1 already done" in res.output
    assert out.read_text().count("foon2asp_results") == 1
