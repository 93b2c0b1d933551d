"""Gravity alone: a run that ends "moving" is repeated with its duration doubled until the stability
rule decides, at most STABILITY_EXTENSION_CAP x the duration asked for (issue #24)."""

import pytest

from blastscale.analysis.gravity_alone import STABILITY_EXTENSION_CAP, extended_keys, until_decided


class _Run:
    """A fake system run whose stability is "moving" until ``settles_at`` [s]."""

    def __init__(self, T, settles_at):
        self.T, self.response = T, self
        self._s = "stands" if T >= settles_at else "moving"

    def summary(self):
        return {"stability": self._s}


@pytest.mark.parametrize(
    "settles_at, final, calls",
    [(1.0, 2.0, [2.0]), (3.0, 4.0, [2.0, 4.0]), (8.0, 8.0, [2.0, 4.0, 8.0]), (1e9, 8.0, [2.0, 4.0, 8.0])],
)
def test_doubles_until_the_rule_decides_up_to_the_cap(settles_at, final, calls):
    seen = []

    def run(T):
        seen.append(T)
        return _Run(T, settles_at)

    r, T = until_decided(run, 2.0)
    assert STABILITY_EXTENSION_CAP == 4.0 and seen == calls[:3] and T == final == r.T
    assert T <= STABILITY_EXTENSION_CAP * 2.0
    if settles_at > 8.0:  # beyond the cap the answer stays "moving"
        assert r.summary()["stability"] == "moving"


def test_with_a_load_nothing_is_extended():
    seen = []
    r, T = until_decided(lambda T: seen.append(T) or _Run(T, 1e9), 2.0, decide=False)
    assert seen == [2.0] and T == 2.0


def test_the_summary_records_an_extension():
    assert extended_keys({"duration_s": 2.0}) == {}
    assert extended_keys({"duration_s": 4.0, "duration_asked_s": 2.0}) == {
        "duration_simulated_s": 4.0,
        "duration_asked_s": 2.0,
        "stability_extension_cap": STABILITY_EXTENSION_CAP,
    }
