"""docs/python.md's example (tests/python/example_replay.py, shown there verbatim: docs.python_snippets) runs, its
printed table is the one the doc quotes, and the settings order as the doc says they do."""
import contextlib
import io
import os

import pytest

import example_replay

DOC = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "docs", "python.md")
MARKER = "<!-- output: tests/python/example_replay.py -->\n```text\n"


@pytest.fixture(scope="module")
def run():
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):
        results = example_replay.main()
    return results, printed.getvalue()


def test_the_doc_quotes_the_examples_output(run):
    _, printed = run
    with open(DOC, encoding="utf-8") as doc:
        text = doc.read()
    assert MARKER in text, "docs/python.md must quote the example's output under its marker"
    quoted = text.split(MARKER, 1)[1].split("```", 1)[0]
    assert quoted == printed


def test_the_settings_trade_samples_for_variance(run):
    results, _ = run
    for budget in (8, 16):
        samples, _ = results[f"cv, budget {budget}"]
        assert abs(samples - budget) <= 0.02 * budget
    # twice the budget: about half the predicted variance (N proportional to sigma, up to the clamps)
    ratio = results["cv, budget 16"][1] / results["cv, budget 8"][1]
    assert 0.4 <= ratio <= 0.6
    # a looser target takes fewer samples for a larger variance
    assert results["cv, target 4e-4"][0] < results["cv, target 1e-4"][0]
    assert results["cv, target 4e-4"][1] > results["cv, target 1e-4"][1]
    # the light change: spvg reads it as noise, cv's control explains it
    assert results["cv, target 1e-4"][0] < 0.8 * results["spvg, target 1e-4"][0]
