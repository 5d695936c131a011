"""Figures readable alone: the deformed picture's magnification."""

import numpy as np
import pytest

from strand.app.plots import magnification


@pytest.mark.parametrize("largest", [1e-7, 3.3e-6, 4e-5, 1.2e-4, 9e-4, 2.4e-3])
def test_magnification_shows_the_largest_displacement_as_a_fifth_to_a_half_of_the_size(largest):
    """A round factor (1, 2 or 5 × 10^k) that brings the largest displacement to between a fifth
    and a half of the strand's diameter, never below 1 (a displacement already that large is
    shown at true scale)."""
    size = 10e-3
    f = magnification(largest, size)
    mantissa = f / 10 ** np.floor(np.log10(f))
    assert f >= 1 and any(np.isclose(mantissa, m) for m in (1, 2, 5))
    if f > 1:
        assert size / 5 <= f * largest <= size / 2 * (1 + 1e-12)
    else:
        assert largest > size / 5
    assert magnification(0.0, size) == 1.0
