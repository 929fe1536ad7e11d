"""``broadsword pattern check``: reports each good file, names each bad one, exits 1 if any."""

from broadsword.cli import main

GOOD = '<bulletml><action label="top"><repeat><times>3</times><action><fire><bullet/></fire><wait>2</wait></action></repeat></action></bulletml>'


def test_check__reports_fired_peak_and_duration(tmp_path, capsys):
    f = tmp_path / "three.xml"
    f.write_text(GOOD)
    assert main(["pattern", "check", str(f)]) == 0
    out = capsys.readouterr().out
    # fires at frames 0, 2, 4; the last wait runs out at frame 6: frames 0..6 are 7 frames
    assert f"{f}: ok: 3 bullets fired, peak 3 live, duration 7 frames" in out


def test_check__names_each_bad_file_and_exits_1(tmp_path, capsys):
    good, bad, missing = tmp_path / "good.xml", tmp_path / "bad.xml", tmp_path / "missing.xml"
    good.write_text(GOOD)
    bad.write_text('<bulletml><action label="top"><wait>1+</wait></action></bulletml>')
    assert main(["pattern", "check", str(bad), str(good), str(missing)]) == 1
    captured = capsys.readouterr()
    assert f"broadsword: {bad}: bulletml/action/wait (line 1): expression '1+': ends too early" in captured.err
    assert f"broadsword: {missing}: cannot read the file" in captured.err
    assert "2 of 3 pattern file(s) failed" in captured.err
    assert f"{good}: ok:" in captured.out


def test_check__params_and_usage_errors(tmp_path, capsys):
    f = tmp_path / "p.xml"
    f.write_text(
        '<bulletml><action label="top"><repeat><times>$1</times><action><fire><bullet/></fire></action>'
        "</repeat></action></bulletml>"
    )
    assert main(["pattern", "check", str(f), "--params", "4"]) == 0
    assert "ok: 4 bullets fired" in capsys.readouterr().out
    assert main(["pattern", "check", str(f), "--rank", "1.5"]) == 2
    assert main(["pattern", "check", str(f), "--params", "x"]) == 2
    assert main(["pattern", "check"]) == 2
    assert main(["pattern", "check", str(f), "--params", "4", "--frames", "36001"]) == 2  # bounded
    assert "must be a whole number in [1, 36,000], got 36001" in capsys.readouterr().err


def test_check__warns_of_each_leniency_and_says_ok_with_the_count(tmp_path, capsys):
    f = tmp_path / "lenient.xml"
    f.write_text(
        '<bulletml><action label="top"><accel label="a"><horizontal></horizontal><term>2</term></accel>'
        "<fire><bullet/></fire></action></bulletml>"
    )
    assert main(["pattern", "check", str(f)]) == 0
    out = capsys.readouterr().out
    assert f"{f}: warning: bulletml/action/accel (line 1): unknown attribute 'label' on <accel> ignored" in out
    assert f"{f}: warning: bulletml/action/accel/horizontal (line 1): empty <horizontal> read as 0" in out
    assert f"{f}: ok (2 warnings): 1 bullets fired" in out
    none = tmp_path / "none.xml"
    none.write_text('<bulletml><action label="main"><fire><bullet/></fire></action></bulletml>')
    assert main(["pattern", "check", str(none)]) == 0
    out = capsys.readouterr().out
    assert "no top action" in out and f"{none}: ok (1 warning): 0 bullets fired" in out


def test_check__a_file_that_needs_parameters_is_not_ok_without_them(tmp_path, capsys):
    f = tmp_path / "p.xml"
    f.write_text(
        '<bulletml><action label="top"><repeat><times>100000</times><action><fire><speed>$1</speed><bullet/></fire>'
        "<wait>$2</wait></action></repeat></action></bulletml>"
    )
    assert main(["pattern", "check", str(f), "--params", "1"]) == 1
    err = capsys.readouterr().err
    assert f"broadsword: {f}: the top actions read $1..$2 (only 1 given): pass them with --params" in err
    assert main(["pattern", "check", str(f), "--params", "1,5", "--frames", "20"]) == 0
    assert "ok: 4 bullets fired" in capsys.readouterr().out


def test_check__warns_of_a_reference_that_passes_too_few_parameters(tmp_path, capsys):
    f = tmp_path / "ref.xml"
    f.write_text(
        '<bulletml><action label="top"><actionRef label="a"><param>1</param></actionRef></action>'
        '<action label="a"><wait>$1 + $3</wait></action></bulletml>'
    )
    assert main(["pattern", "check", str(f)]) == 0
    assert "reads $3 but a <actionRef> to it passes 1 parameter (the rest read 0)" in capsys.readouterr().out
