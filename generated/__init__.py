"""Emitted code only: every module here is written by ``derive``, never edited by hand."""
