"""Test set-ups: the supports, loads and measurements of a strand test (``base.TestSetup``)."""

from .base import PenaltyLinks, TestSetup
from .bending import UniformBendingTest
from .saddle import SaddleTest

__all__ = ["TestSetup", "PenaltyLinks", "SaddleTest", "UniformBendingTest"]
