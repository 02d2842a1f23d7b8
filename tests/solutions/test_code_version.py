"""The code version a stored solution is keyed by: the sources hashed once per install, never stale."""
import hashlib

from spinorbit.solutions import code_version as cv


def hashed_directly(package):
    """The content hash computed from the files' bytes alone (the definition, no record)."""
    digest = hashlib.sha256()
    for name, _ in cv.sources(package):
        digest.update(name.encode() + b"\0" + (package / name).read_bytes())
    return digest.hexdigest()[:16]


def test_the_record_is_reused_and_any_change_is_hashed_again(tmp_path, monkeypatch):
    package, cache = tmp_path / "pkg", tmp_path / "cache"
    (package / "sub").mkdir(parents=True)
    cache.mkdir()
    (package / "a.py").write_text("x = 1\n")
    (package / "sub" / "b.py").write_text("y = 2\n")
    first = cv.content_version(package, cache)
    assert first == hashed_directly(package)
    monkeypatch.setattr(cv, "content_hash", lambda *a: "not hashed again")
    assert cv.content_version(package, cache) == first                   # the record answers, nothing rehashed
    monkeypatch.undo()
    (package / "sub" / "b.py").write_text("y = 3\n")           # same size, new content
    assert cv.content_version(package, cache) == hashed_directly(package) != first
    (package / "c.py").write_text("")                          # a new file
    assert cv.content_version(package, cache) == hashed_directly(package)


def test_an_unreadable_record_is_refused_in_one_line_and_made_again(tmp_path, capfd):
    package, cache = tmp_path / "pkg", tmp_path / "cache"
    package.mkdir()
    cache.mkdir()
    (package / "a.py").write_text("x = 1\n")
    path = cv.record_path(cache, package)
    stamp = cv.fingerprint(cv.sources(package))
    for damaged in ('{"fingerprint": "', f'{{"fingerprint": "{stamp}", "content": 12}}'):   # truncated, altered
        path.write_text(damaged)
        assert cv.content_version(package, cache) == hashed_directly(package)
        said = [line for line in capfd.readouterr().err.splitlines() if "refused" in line]
        assert len(said) == 1 and str(path) in said[0]
        assert cv.stored(path, stamp) == hashed_directly(package)


def test_a_folder_in_place_of_the_record_is_replaced(tmp_path):
    """Found by benchmarks/fuzz_store.py: a folder where the record belongs was a traceback (os.replace)."""
    package, cache = tmp_path / "pkg", tmp_path / "cache"
    package.mkdir()
    cache.mkdir()
    (package / "a.py").write_text("x = 1\n")
    path = cv.record_path(cache, package)
    path.mkdir()
    (path / "inside").write_text("x")
    assert cv.content_version(package, cache) == hashed_directly(package)
    assert path.is_file()
