"""`spinorbit show` (spinorbit.edge.key_table): the scene's sentence whole and every key's meaning whole at any terminal
width."""
from spinorbit.edge.cli import main


def words(text):
    return " ".join(text.split())


def test_show_ends_the_scenes_sentence_and_prints_every_meaning_whole(monkeypatch, capsys):
    from spinorbit.edge.key_table import key_table

    heading, rows = key_table("earth_deep_time")
    assert heading.endswith("gives it.")                          # the docstring's first paragraph, whole
    for columns in ("80", "200"):
        monkeypatch.setenv("COLUMNS", columns)
        assert main(["show", "earth_deep_time"]) == 0
        out = words(capsys.readouterr().out)
        assert words(heading) in out
        assert all(words(row[-1]) in out and row[0] in out for row in rows)
        title = "\"Earth's obliquity and precession, 1 Myr back, vs La2004\""         # the file's, wrapped in its cell
        assert all(word in out.split() for word in title.split())
