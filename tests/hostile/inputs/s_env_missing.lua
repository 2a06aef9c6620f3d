scene.environment "e" { kind = "hdr", file = "nope.hdr" }
