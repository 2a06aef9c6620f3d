for i = 1, 9 do scene.probe("p" .. i) {} end
