"""Placeholder: filled in by the SEC-applications work (issue 16)."""


def test_placeholder():
    pass
