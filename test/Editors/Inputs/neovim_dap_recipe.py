#!/usr/bin/env python3
"""Writes an init.lua for neovim-dap.test: a stand-in `dap` module (the
tables nvim-dap reads), then the Lua block of docs/editors.md's "In Neovim
(nvim-dap)" section as it stands, then a harness that writes what the
block declared as JSON to OUT, with `${file}` as nvim-dap expands it (the
buffer's file), and quits.

    neovim_dap_recipe.py EDITORS_MD OUT > init.lua
"""
import re
import sys

doc, out = sys.argv[1:3]
text = open(doc, encoding="utf-8").read()
section = text.split("### In Neovim (nvim-dap)", 1)[1]
block = re.search(r"```lua\n(.*?)```", section, re.S).group(1)
print("""package.loaded['dap'] = { adapters = {}, configurations = {} }""")
print(block)
print("""
vim.api.nvim_create_autocmd('VimEnter', {
  callback = function()
    local dap = require('dap')
    local file = vim.fn.expand('%%:p')
    local configs = {}
    for _, c in ipairs(dap.configurations.bscript or {}) do
      local expanded = {}
      for k, v in pairs(c) do
        expanded[k] = type(v) == 'string' and v:gsub('%%${file}', file) or v
      end
      table.insert(configs, expanded)
    end
    local f = io.open('%s', 'w')
    f:write(vim.fn.json_encode({ adapter = dap.adapters.bscript,
                                 configurations = configs }))
    f:close()
    vim.cmd('qa!')
  end,
})""" % out)
