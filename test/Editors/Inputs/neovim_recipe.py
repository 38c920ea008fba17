#!/usr/bin/env python3
"""Writes an init.lua for neovim.test: the Lua block of docs/editors.md's
"Neovim 0.7" section as it stands, with `bsc` replaced by the bsc under
test, then a harness that waits for the server's diagnostics of the
buffer and writes them (line, message) to OUT before quitting.

    neovim_recipe.py EDITORS_MD BSC OUT > init.lua
"""
import re
import sys

doc, bsc, out = sys.argv[1:4]
text = open(doc, encoding="utf-8").read()
section = text.split("### Neovim 0.7", 1)[1]
block = re.search(r"```lua\n(.*?)```", section, re.S).group(1)
if "'bsc', 'lsp'" not in block:
    sys.exit("the recipe no longer starts 'bsc', 'lsp'")
print(block.replace("'bsc', 'lsp'", "'%s', 'lsp'" % bsc))
print("""
vim.api.nvim_create_autocmd('VimEnter', {
  callback = function()
    local ok = vim.wait(20000, function()
      return #vim.diagnostic.get(0) > 0
    end, 50)
    local f = io.open('%s', 'w')
    f:write('filetype ' .. vim.bo.filetype .. '\\n')
    f:write('clients ' .. #vim.lsp.buf_get_clients(0) .. '\\n')
    if not ok then f:write('no diagnostics\\n') end
    for _, d in ipairs(vim.diagnostic.get(0)) do
      f:write(string.format('%%d: %%s\\n', d.lnum + 1, d.message))
    end
    f:close()
    vim.cmd('qa!')
  end,
})""" % out)
