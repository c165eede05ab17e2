"""Unit tests of owl_path_index.py: the indexed finder finds what Python's own finds, asking fewer folders.

The module is loaded from its source beside test/ (every process of the venv runs its copy).
"""

import importlib.util
import sys
from importlib.machinery import PathFinder
from pathlib import Path

import pytest

SOURCE = Path(__file__).resolve().parents[1] / 'owl_path_index.py'
spec = importlib.util.spec_from_file_location('owl_path_index_under_test', SOURCE)
assert spec is not None
assert spec.loader is not None
index = importlib.util.module_from_spec(spec)
spec.loader.exec_module(index)
Finder = index.IndexedPathFinder


@pytest.fixture
def folders(tmp_path, monkeypatch):
    """Thirty empty folders ahead of sys.path, then three with modules, packages and namespace portions."""
    empty = [tmp_path / f'empty{number}' for number in range(30)]
    first, second, third = tmp_path / 'first', tmp_path / 'second', tmp_path / 'third'
    for folder in [*empty, first, second, third]:
        folder.mkdir()
    (first / 'alone.py').write_text('WHERE = "first"\n')
    (first / 'portion').mkdir()  # a namespace portion here ...
    (first / 'portion' / 'in_first.py').write_text('')
    (second / 'portion').mkdir()  # ... and another one here
    (second / 'portion' / 'in_second.py').write_text('')
    (first / 'shadowed').mkdir()  # a namespace portion, then a regular package of the same name
    (third / 'shadowed').mkdir()
    (third / 'shadowed' / '__init__.py').write_text('')
    (second / 'alone.py').write_text('WHERE = "second"\n')  # found later in sys.path: not the one
    (third / 'compiled.cpython-311-x86_64-linux-gnu.so').write_bytes(b'')
    monkeypatch.setattr(sys, 'path', [*map(str, [*empty, first, second, third]), *sys.path])
    Finder.invalidate_caches()
    yield first, second, third
    Finder.invalidate_caches()


def origin_and_locations(found):
    return None if found is None else (found.origin, found.submodule_search_locations and
                                       list(found.submodule_search_locations))


@pytest.mark.parametrize('name', ['alone', 'portion', 'shadowed', 'compiled', 'json', 'pytest', 'not_there'])
def test_it_finds_what_pythons_own_search_finds(folders, name):
    assert origin_and_locations(Finder.find_spec(name)) == origin_and_locations(PathFinder.find_spec(name))


def test_a_name_is_looked_for_only_in_the_folders_that_have_it(folders):
    first, second, third = map(str, folders)
    asked = Finder._candidates('portion')
    assert first in asked
    assert second in asked
    assert third not in asked
    assert not any('empty' in folder for folder in asked)
    assert Finder._candidates('alone')[:2] == [first, second]


def test_a_module_written_after_its_folder_was_listed_is_found(folders):
    first = folders[0]
    assert Finder.find_spec('written_later') is None
    (first / 'written_later.py').write_text('')
    found = Finder.find_spec('written_later')
    assert found is not None
    assert found.origin == str(first / 'written_later.py')


def test_a_folder_not_there_yet_or_relative_is_always_asked(folders, tmp_path, monkeypatch):
    later = tmp_path / 'later'
    monkeypatch.setattr(sys, 'path', ['', 'relative', str(later), *sys.path])
    assert Finder._candidates('anything')[:3] == ['', 'relative', str(later)]
    later.mkdir()
    (later / 'arrived.py').write_text('')
    found = Finder.find_spec('arrived')
    assert found is not None
    assert found.origin == str(later / 'arrived.py')


def test_a_submodule_is_searched_in_its_packages_folders(folders):
    first, second, _ = folders
    found = Finder.find_spec('portion.in_second', [str(first / 'portion'), str(second / 'portion')])
    assert found is not None
    assert found.origin == str(second / 'portion' / 'in_second.py')


def test_install_takes_the_place_of_pythons_path_finder_once(monkeypatch):
    meta_path = [object(), PathFinder, object()]
    monkeypatch.setattr(sys, 'meta_path', meta_path)
    index.install()
    index.install()
    assert meta_path[1] is Finder
    assert PathFinder not in meta_path
    assert len(meta_path) == 3
