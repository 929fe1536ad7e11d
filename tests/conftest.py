"""Test setup: every test runs headless (SDL's dummy video and audio drivers), with a scratch cache."""

import os
import tempfile

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
os.environ.setdefault("SDL_AUDIODRIVER", "dummy")
# rendered music goes to a scratch cache, never the user's (games started by tests inherit it)
os.environ.setdefault("BROADSWORD_CACHE_DIR", tempfile.mkdtemp(prefix="broadsword-test-cache-"))
