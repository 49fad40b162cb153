"""pool_env.render: top-down frames of the table, shot playback, text overlays and the pygame window."""
