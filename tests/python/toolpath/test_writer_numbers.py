"""The G-code writer formats any finite number whole (it once copied past a 64-byte buffer: NUL bytes and
63-digit F words) and refuses feeds above F 1e8 mm/min with the field and value (docs/toolpath.md)."""

from __future__ import annotations

import re

import pytest

from netshape import toolpath as tpm


def _one_block(**changes):
    tp = tpm.parse_gcode("G1 X1 F600\n")
    b = tp.blocks[0]
    for k, v in changes.items():
        setattr(b, k, v)
    return tp.with_blocks([b], [0])


@pytest.mark.parametrize("x", [1e300, -1.7976931348623157e308, 5e-324, 1.2345678901234567e80])
@pytest.mark.parametrize("decimals", [-1, 0, 12])
def test_long_numbers_are_written_whole(x, decimals):
    """The reader refuses |X| > 1e9 mm, so the words are read back here as numbers."""
    text = tpm.format_gcode(_one_block(end=[x, 0.0, 0.0]), decimals=decimals)
    assert "\0" not in text
    word = re.search(r"\bX(\S+)", text).group(1)
    if decimals == -1 or abs(x) >= 1:
        assert len(word) > 63  # longer than the old 64-byte buffer
        assert float(word) == x
    else:
        assert float(word) == 0.0


@pytest.mark.parametrize("feed_mm_s", [1e60 / 60, 1e8 / 60 * 1.000001, 1e300])
def test_feeds_above_the_bound_are_refused(feed_mm_s):
    with pytest.raises(ValueError, match=r"^block.feed = .*: must not exceed .*F 1e8 mm/min"):
        tpm.format_gcode(_one_block(feed=feed_mm_s))


def test_the_bound_itself_is_written():
    text = tpm.format_gcode(_one_block(feed=1e8 / 60))
    assert "F100000000" in text
