"""Tests of voot.record.blueprint: the default viewer layout."""

from __future__ import annotations

import pytest

rrb = pytest.importorskip("rerun.blueprint")

from voot.record.blueprint import default_blueprint  # noqa: E402


def _views(container: object) -> list[object]:
    out: list[object] = []
    for part in container.contents:  # type: ignore[attr-defined]
        out.extend(_views(part) if isinstance(part, rrb.Container) else [part])
    return out


@pytest.mark.parametrize(("scene", "plot"), [(True, False), (True, True), (False, True)])
def test_layout(scene: bool, plot: bool) -> None:
    bp = default_blueprint(has_scene=scene, has_plot=plot)
    assert isinstance(bp, rrb.Blueprint)
    views = _views(bp.root_container)
    kinds = [type(v).__name__ for v in views]
    assert kinds.count("GraphView") == 1
    assert kinds.count("TimeSeriesView") == 3
    assert kinds.count("Spatial3DView") == (1 if scene else 0)
    assert kinds.count("Spatial2DView") == (1 if plot else 0)
    origins = {str(v.origin) for v in views}  # type: ignore[attr-defined]
    assert {"/search/best_return", "/search/n_nodes", "/tree"} <= origins
    no_plan = default_blueprint(has_scene=scene, has_plot=plot, has_plan=False)
    assert [type(v).__name__ for v in _views(no_plan.root_container)].count("TimeSeriesView") == 2


def test_plan_rewards_show_on_the_search_timeline() -> None:
    """The layout opens on the search timeline: the plan's rewards are a static bar chart."""
    views = _views(default_blueprint(has_scene=True, has_plot=False).root_container)
    bars = [v for v in views if type(v).__name__ == "BarChartView"]
    assert [str(v.origin) for v in bars] == ["/plan/rewards"]  # type: ignore[attr-defined]


def test_the_3d_view_opens_at_the_given_eye() -> None:
    from voot.record.blueprint import Eye3D

    eye = Eye3D((-3.9, -7.0, 6.2), (1.6, 0.3, 0.0))
    (main,) = [
        v
        for v in _views(default_blueprint(has_scene=True, has_plot=True, eye=eye).root_container)
        if type(v).__name__ == "Spatial3DView"
    ]
    controls = main.properties["EyeControls3D"]  # type: ignore[attr-defined]
    # rerun stores float32
    assert controls.position.as_arrow_array().to_pylist() == [pytest.approx([-3.9, -7.0, 6.2])]
    assert controls.look_target.as_arrow_array().to_pylist() == [pytest.approx([1.6, 0.3, 0.0])]
    assert controls.eye_up.as_arrow_array().to_pylist() == [[0.0, 0.0, 1.0]]
    assert controls.kind.as_arrow_array().to_pylist() == [rrb.components.Eye3DKind.Orbital.value]
    (auto,) = [
        v
        for v in _views(default_blueprint(has_scene=True, has_plot=False).root_container)
        if type(v).__name__ == "Spatial3DView"
    ]
    assert "EyeControls3D" not in auto.properties  # type: ignore[attr-defined]


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"position": (0.0, 0.0), "look_target": (1.0, 0.0, 0.0)}, "position must be 3 finite"),
        ({"position": (0.0, 0.0, 1.0), "look_target": (0.0, float("nan"), 0.0)}, "look_target"),
        ({"position": (1.0, 1.0, 1.0), "look_target": (1.0, 1.0, 1.0)}, "must differ"),
        ({"position": (0, 0, 1), "look_target": (0, 0, 0), "up": (0, 0, 0)}, "zero vector"),
    ],
)
def test_eye_validation(kwargs: dict[str, object], match: str) -> None:
    from voot.record.blueprint import Eye3D

    with pytest.raises(ValueError, match=match):
        Eye3D(**kwargs)  # type: ignore[arg-type]
