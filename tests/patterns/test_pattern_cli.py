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
