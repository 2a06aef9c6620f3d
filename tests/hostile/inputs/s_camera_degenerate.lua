scene.camera "c" { position = { 0, 0, 0 }, target = { 0, 0, 0 } }
