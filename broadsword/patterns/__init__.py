"""Bullet patterns: the BulletML reader and runner (numpy + standard library only)."""
