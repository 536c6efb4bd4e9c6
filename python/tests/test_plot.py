"""Result.plot: the figure `nsbridge plot` draws, with matplotlib (Agg), from the Result's
history, grouped by the contact families of summary.json."""
import matplotlib

matplotlib.use("Agg")

import pytest  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

import nsbridge  # noqa: E402
from conftest import SOURCE  # noqa: E402

# The two-frame bridge (docs/outputs.md, "Contact order of a deck in several bodies"): two
# bodies; contacts 1-2 the left seat, 3-4 the hinge, 5-6 the right seat. Its first impacts
# come before 5 s.
SHORT = ["solver.end_time=5", "solver.error_estimate=false"]


@pytest.fixture(scope="module")
def two_frame():
    return nsbridge.run(SOURCE / "scenes/bridge-two-frame.toml", method="moreau", overrides=SHORT)


def labels(ax):
    """The labelled curves of ax (matplotlib names an unlabelled line, as the dashed g = 0 of a
    gap panel, with a leading underscore)."""
    return [line.get_label() for line in ax.get_lines() if not line.get_label().startswith("_")]


def test_the_response_groups_bodies_and_contact_families(two_frame, tmp_path):
    axes = two_frame.plot()
    assert [a.get_title() for a in axes] == ["displacements", "rotations", "abutments", "hinges"]
    assert labels(axes[0]) == ["x1 (body 1)", "y1 (body 1)", "x2 (body 2)", "y2 (body 2)"]
    assert labels(axes[1]) == ["theta1 (body 1)", "theta2 (body 2)"]
    assert labels(axes[2]) == ["gN1: left +W/2", "gN2: left -W/2",
                               "gN5: right +W/2", "gN6: right -W/2"]
    assert labels(axes[3]) == ["gN3: hinge 1 +W/2", "gN4: hinge 1 -W/2"]
    assert [a.get_ylabel() for a in axes] == ["displacement [m]", "rotation [rad]",
                                              "normal gap [m]", "normal gap [m]"]
    fig = axes[0].figure
    assert fig._suptitle.get_text() == "bridge-two-frame: response, Moreau-Jean time stepping"
    fig.savefig(tmp_path / "response.png")
    assert (tmp_path / "response.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_gaps_energy_and_events(two_frame):
    gaps = two_frame.plot("gaps")
    # Each family's gaps and the dashed zero line.
    assert [len(a.get_lines()) for a in gaps] == [5, 3]
    energy = two_frame.plot("energy")
    assert labels(energy[0]) == ["energy_error"]
    (events,) = two_frame.plot("events")
    kinds = set(two_frame.events["kind"])
    assert sorted(labels(events)) == sorted(kinds)


def test_drawn_into_given_axes(two_frame):
    fig = Figure()
    given = fig.subplots(4, 1)
    drawn = two_frame.plot("response", ax=given)
    assert drawn == list(given)
    with pytest.raises(ValueError, match="draws 4 panels; ax holds 1"):
        two_frame.plot("response", ax=Figure().subplots())


def test_bents_need_their_columns_and_an_unknown_kind_is_refused(two_frame):
    with pytest.raises(ValueError, match=r'groups = \["bents"\]'):
        two_frame.plot("bents")
    with pytest.raises(ValueError, match="what='loops'"):
        two_frame.plot("loops")
