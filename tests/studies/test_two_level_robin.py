"""The two-level Robin study's band rule: the fine loop's gamma times sqrt(h H), the fine
and coarse interface elements, is the same at every mesh level (the element rule's at
mesh level 1), while the element rule keeps gamma itself."""

import math

import pytest

from orchestrate.ddm import coarse_element_size
from orchestrate.model import Settings
from studies.two_level_robin import two_level_settings


@pytest.mark.parametrize("factor", [2.0, 4.0])
def test_the_band_rule_keeps_gamma_times_the_bands_geometric_mean(factor):
    def gamma_times_mean(rule, level):
        at = two_level_settings(Settings(coarse_element_factor=factor), level, rule, "auto")
        return at.robin_parameter * math.sqrt(at.element_length / level
                                              * coarse_element_size(at))
    first = gamma_times_mean("element", 1)
    for level in (1, 2, 3):
        assert gamma_times_mean("band", level) == pytest.approx(first, rel=1e-12)
        element = two_level_settings(Settings(coarse_element_factor=factor), level,
                                     "element", "auto")
        default = Settings()
        assert element.robin_parameter == (default.robin_two_level_per_length
                                           / default.element_length)
